// Scans of known scenes for the mapping tests, made with the simulator's sensors.
#pragma once

#include <Eigen/Geometry>

#include "mmh/mapping/scan_filter.hpp"
#include "mmh/sim/forest_world.hpp"
#include "mmh/sim/sensor.hpp"

namespace mmh::test {

inline sim::Scan scanOf(const sim::World& world, const Eigen::Vector3d& position, double yaw_deg,
                        sim::SensorKind kind = sim::SensorKind::kDepth, int free_ray_stride = 1) {
  sim::SimParams params;
  params.free_ray_stride = free_ray_stride;
  sim::Sensor sensor(kind, params, 1);
  sim::Scan scan;
  sensor.scan(
      world, position,
      Eigen::Quaterniond(Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ())),
      &scan);
  return scan;
}

inline mapping::ScanInput inputOf(const sim::Scan& scan) {
  mapping::ScanInput in;
  in.sensor_position = scan.position;
  in.max_range_m = scan.max_range_m;
  in.xyz = scan.xyz.data();
  in.num_points = scan.xyz.size() / 3;
  return in;
}

// A few pillars around (0, 0) at 1.5 - 4 m, one hidden behind another as seen from the origin.
inline sim::ForestWorld smallForest() {
  return sim::ForestWorld({
      Cylinder{Eigen::Vector2d(2.0, 0.0), 0.3, 0.0, 3.0},
      Cylinder{Eigen::Vector2d(3.6, 0.0), 0.25, 0.0, 3.0},  // behind the first (from the origin)
      Cylinder{Eigen::Vector2d(1.5, 2.0), 0.4, 0.0, 3.0},
      Cylinder{Eigen::Vector2d(-2.5, 1.0), 0.2, 0.0, 3.0},
      Cylinder{Eigen::Vector2d(-1.0, -3.0), 0.5, 0.0, 3.0},
      Cylinder{Eigen::Vector2d(0.5, -2.0), 0.15, 0.0, 3.0},
  });
}

}  // namespace mmh::test
