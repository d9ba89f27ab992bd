#include "mmh/sim/world_file.hpp"

#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "mmh/common/config_validation.hpp"
#include "mmh/common/forest.hpp"
#include "mmh/sim/ego_forest.hpp"
#include "mmh/sim/simulator.hpp"

namespace mmh::sim {
namespace {

std::string triple(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return out.str();
}

// Steps of at most `spacing` over a length: at least one.
int steps(double length, double spacing) {
  return std::max(1, static_cast<int>(std::ceil(length / spacing)));
}

void addCylinder(const Cylinder& c, double spacing, std::vector<Eigen::Vector3f>* out) {
  const int around = std::max(8, steps(2.0 * M_PI * c.radius, spacing));
  const int up = steps(c.z_max - c.z_min, spacing);
  for (int k = 0; k <= up; ++k) {
    const double z = c.z_min + (c.z_max - c.z_min) * k / up;
    for (int i = 0; i < around; ++i) {
      const double a = 2.0 * M_PI * i / around;
      out->emplace_back(static_cast<float>(c.center.x() + c.radius * std::cos(a)),
                        static_cast<float>(c.center.y() + c.radius * std::sin(a)),
                        static_cast<float>(z));
    }
  }
  // The top disc (a ray from above must hit it, too).
  for (int ring = 1; ring < steps(c.radius, spacing); ++ring) {
    const double r = c.radius * ring / steps(c.radius, spacing);
    const int n = std::max(6, steps(2.0 * M_PI * r, spacing));
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * M_PI * i / n;
      out->emplace_back(static_cast<float>(c.center.x() + r * std::cos(a)),
                        static_cast<float>(c.center.y() + r * std::sin(a)),
                        static_cast<float>(c.z_max));
    }
  }
  out->emplace_back(static_cast<float>(c.center.x()), static_cast<float>(c.center.y()),
                    static_cast<float>(c.z_max));
}

// A column's box [x0, x0 + e] x [y0, y0 + e] x [0, h]: its four sides and its top.
void addColumn(const EgoColumn& c, double spacing, std::vector<Eigen::Vector3f>* out) {
  const double e = kEgoColumnEdgeM, x0 = c.ix * e, y0 = c.iy * e, h = c.height_m;
  if (!(h > 0.0)) return;
  const int across = steps(e, spacing), up = steps(h, spacing);
  for (int k = 0; k <= up; ++k) {
    const double z = h * k / up;
    for (int i = 0; i <= across; ++i) {
      const double s = e * i / across;
      for (const Eigen::Vector3d& p :
           {Eigen::Vector3d(x0 + s, y0, z), Eigen::Vector3d(x0 + s, y0 + e, z),
            Eigen::Vector3d(x0, y0 + s, z), Eigen::Vector3d(x0 + e, y0 + s, z)}) {
        out->push_back(p.cast<float>());
      }
    }
  }
  for (int i = 0; i <= across; ++i) {
    for (int j = 0; j <= across; ++j) {
      out->emplace_back(static_cast<float>(x0 + e * i / across),
                        static_cast<float>(y0 + e * j / across), static_cast<float>(h));
    }
  }
}

void addRing(const EllipticRing& r, double spacing, std::vector<Eigen::Vector3f>* out) {
  const Eigen::Vector3d normal(std::cos(r.yaw), std::sin(r.yaw), 0.0);
  const Eigen::Vector3d along(-std::sin(r.yaw), std::cos(r.yaw), 0.0), up(0.0, 0.0, 1.0);
  const double a = r.semi_horizontal_m, b = r.semi_vertical_m;
  const double perimeter = M_PI * (3.0 * (a + b) - std::sqrt((3.0 * a + b) * (a + 3.0 * b)));
  const int n = steps(perimeter, spacing);
  const int m = std::max(6, steps(2.0 * M_PI * r.tube_radius_m, spacing));
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * i / n;
    const Eigen::Vector3d c = r.center + a * std::cos(t) * along + b * std::sin(t) * up;
    // The ellipse's outward normal in its plane.
    const Eigen::Vector3d out_n = (std::cos(t) / a * along + std::sin(t) / b * up).normalized();
    for (int j = 0; j < m; ++j) {
      const double phi = 2.0 * M_PI * j / m;
      const Eigen::Vector3d p =
          c + r.tube_radius_m * (std::cos(phi) * normal + std::sin(phi) * out_n);
      out->push_back(p.cast<float>());
    }
  }
}

}  // namespace

bool isPcdWorld(const std::string& world) {
  const std::string suffix = ".pcd";
  return world.size() >= suffix.size() &&
         world.compare(world.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::vector<Eigen::Vector3f> readPcdPoints(const std::string& path) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  int status = -1;
  try {
    status = pcl::io::loadPCDFile<pcl::PointXYZ>(path, cloud);
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot read PCD file " + path + ": " + e.what());
  }
  if (status < 0) throw std::runtime_error("cannot read PCD file " + path);
  std::vector<Eigen::Vector3f> points;
  points.reserve(cloud.size());
  for (const auto& p : cloud) points.emplace_back(p.x, p.y, p.z);
  return points;
}

WorldBounds readPcdBounds(const std::string& path) {
  WorldBounds b;
  b.min_m = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  b.max_m = -b.min_m;
  bool any = false;
  for (const Eigen::Vector3f& p : readPcdPoints(path)) {
    const Eigen::Vector3d q = p.cast<double>();
    if (!q.allFinite()) continue;
    b.min_m = b.min_m.cwiseMin(q);
    b.max_m = b.max_m.cwiseMax(q);
    any = true;
  }
  if (!any) throw std::runtime_error("PCD file " + path + " holds no finite point");
  return b;
}

std::string worldBoundsViolation(const WorldBounds& bounds, const Eigen::Vector3d& p,
                                 const std::string& what, const std::string& world_name) {
  std::ostringstream axes_out;
  const char* axes = "xy";
  bool first = true;
  for (int i = 0; i < 2; ++i) {
    if (!(p[i] >= bounds.min_m[i] && p[i] <= bounds.max_m[i])) {
      axes_out << (first ? "" : ", ") << axes[i] << " = " << p[i]
               << (p[i] < bounds.min_m[i] ? " < " : " > ")
               << (p[i] < bounds.min_m[i] ? bounds.min_m[i] : bounds.max_m[i]);
      first = false;
    }
  }
  if (first) return "";
  std::ostringstream out;
  out << what << " " << triple(p) << " lies outside the world's bounds (" << axes_out.str()
      << "): " << world_name << " spans x [" << bounds.min_m.x() << ", " << bounds.max_m.x()
      << "], y [" << bounds.min_m.y() << ", " << bounds.max_m.y() << "], z [" << bounds.min_m.z()
      << ", " << bounds.max_m.z() << "]; move it into the world";
  return out.str();
}

std::string startGoalViolation(const Eigen::Vector3d& start, const Eigen::Vector3d& goal,
                               const Geofence& fence, const WorldBounds* bounds,
                               const std::string& world_name) {
  for (const auto& [point, name] : {std::pair{start, "the start"}, std::pair{goal, "the goal"}}) {
    std::string why = geofenceViolation(fence, point, name);
    if (why.empty() && bounds) why = worldBoundsViolation(*bounds, point, name, world_name);
    if (!why.empty()) return why;
  }
  return "";
}

Geofence fitGeofence(const WorldBounds& bounds, const Geofence& configured, double margin_xy_m) {
  Geofence fence = configured;
  for (int i = 0; i < 2; ++i) {
    fence.min_m[i] = std::floor((bounds.min_m[i] - margin_xy_m) * 100.0) / 100.0;
    fence.max_m[i] = std::ceil((bounds.max_m[i] + margin_xy_m) * 100.0) / 100.0;
  }
  return fence;
}

Geofence fitGeofenceToPcd(const std::string& path, const Config& config, std::string* report) {
  if (!isPcdWorld(path)) {
    throw std::runtime_error("--fit-geofence needs a PCD world (--world FILE.pcd), not '" + path +
                             "'");
  }
  const WorldBounds bounds = readPcdBounds(path);
  const Geofence fence = fitGeofence(bounds, loadGeofence(config));
  if (report) {
    *report = "--fit-geofence: geofence.min_m = " + triple(fence.min_m) +
              ", geofence.max_m = " + triple(fence.max_m) + " (" + path + " spans " +
              triple(bounds.min_m) + " to " + triple(bounds.max_m) +
              "; 1 m margin in x and y, z as configured)";
  }
  return fence;
}

std::vector<std::string> geofenceAssignments(const Geofence& fence) {
  return {"geofence.min_m=" + triple(fence.min_m), "geofence.max_m=" + triple(fence.max_m)};
}

Config configWithGeofence(const Config& config, const Geofence& fence) {
  YAML::Node root = YAML::Clone(config.root());
  for (const auto& [key, v] : {std::pair{"min_m", fence.min_m}, std::pair{"max_m", fence.max_m}}) {
    YAML::Node seq(YAML::NodeType::Sequence);
    seq.SetStyle(YAML::EmitterStyle::Flow);
    for (int i = 0; i < 3; ++i) seq.push_back(v[i]);
    root["geofence"][key] = seq;
  }
  std::ostringstream out;
  out << root;
  Config fitted = Config::fromString(out.str(), config.source() + " with --fit-geofence");
  validateConfig(fitted);
  return fitted;
}

std::vector<Eigen::Vector3f> generatedWorldPoints(const SimOptions& options, double spacing_m) {
  if (!(spacing_m > 0.0)) throw std::runtime_error("the point spacing must be positive");
  std::vector<Eigen::Vector3f> points;
  try {
    if (options.world == "forest") {
      for (const Cylinder& c : generateForest(forestSpecOf(options)))
        addCylinder(c, spacing_m, &points);
      return points;
    }
    if (options.world == "ego-forest") {
      const EgoForest forest = generateEgoForest(egoForestSpecOf(options));
      for (const EgoPillar& p : forest.pillars) {
        for (const EgoColumn& c : p.columns) addColumn(c, spacing_m, &points);
      }
      for (const EllipticRing& r : forest.rings) addRing(r, spacing_m, &points);
      return points;
    }
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  throw std::runtime_error("--export-world writes a generated world (forest or ego-forest), not '" +
                           options.world + "'");
}

void writePcd(const std::string& path, const std::vector<Eigen::Vector3f>& points) {
  if (points.empty()) throw std::runtime_error("the world has no obstacle to write to " + path);
  pcl::PointCloud<pcl::PointXYZ> cloud;
  cloud.reserve(points.size());
  for (const Eigen::Vector3f& p : points) cloud.push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  cloud.width = static_cast<uint32_t>(cloud.size());
  cloud.height = 1;
  cloud.is_dense = true;
  int status = -1;
  try {
    status = pcl::io::savePCDFileBinary(path, cloud);
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot write PCD file " + path + ": " + e.what());
  }
  if (status < 0) throw std::runtime_error("cannot write PCD file " + path);
}

std::string exportWorld(const SimOptions& options, const std::string& path) {
  const std::vector<Eigen::Vector3f> points = generatedWorldPoints(options);
  writePcd(path, points);
  std::ostringstream report;
  report << "wrote " << points.size() << " surface points of the " << options.world << " (seed "
         << options.seed << ", density " << options.density_per_m2 << " /m^2) to " << path;
  return report.str();
}

}  // namespace mmh::sim
