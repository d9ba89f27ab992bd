#include "mmh/common/geofence.hpp"

#include <sstream>

namespace mmh {

Geofence loadGeofence(const Config& config) {
  // That max_m exceeds min_m is a registered constraint (config_constraints.cpp), checked with
  // the others by every parameter loader.
  return {config.getVector3("geofence.min_m"), config.getVector3("geofence.max_m")};
}

bool insideBox(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
}

bool insideGeofence(const Geofence& fence, const Eigen::Vector3d& p) {
  return insideBox(p, fence.min_m, fence.max_m);
}

Box fenceForStart(const Eigen::Vector3d& min_m, const Eigen::Vector3d& max_m,
                  const Eigen::Vector3d& start, double tolerance_m) {
  const Eigen::Vector3d grow = Eigen::Vector3d::Constant(tolerance_m);
  if (insideBox(start, min_m, max_m) || !insideBox(start, min_m - grow, max_m + grow))
    return {min_m, max_m};
  return {min_m - grow, max_m + grow};
}

std::string geofenceViolation(const Geofence& fence, const Eigen::Vector3d& p,
                              const std::string& what) {
  if (insideGeofence(fence, p)) return "";
  const auto triple = [](const Eigen::Vector3d& v) {
    std::ostringstream out;
    out << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
    return out.str();
  };
  std::ostringstream out;
  out << what << " " << triple(p) << " lies outside the geofence (";
  const char* axes = "xyz";
  bool first = true;
  for (int i = 0; i < 3; ++i) {
    if (!(p[i] >= fence.min_m[i] && p[i] <= fence.max_m[i])) {
      out << (first ? "" : ", ") << axes[i] << " = " << p[i]
          << (p[i] < fence.min_m[i] ? " < " : " > ")
          << (p[i] < fence.min_m[i] ? fence.min_m[i] : fence.max_m[i]);
      first = false;
    }
  }
  out << "): geofence.min_m = " << triple(fence.min_m)
      << ", geofence.max_m = " << triple(fence.max_m)
      << "; widen them in the configuration (or --set)";
  return out.str();
}

}  // namespace mmh
