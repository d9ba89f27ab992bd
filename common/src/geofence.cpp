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

Geofence fenceForStart(const Geofence& fence, const Eigen::Vector3d& start, double tolerance_m) {
  const Geofence grown{fence.min_m - Eigen::Vector3d::Constant(tolerance_m),
                       fence.max_m + Eigen::Vector3d::Constant(tolerance_m)};
  if (insideGeofence(fence, start) || !insideGeofence(grown, start)) return fence;
  return grown;
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
