// Sensor frames along a collision-free flight through a forest of the benchmark protocol, for
// the mapping benchmarks: the shortest path (discs inflated by 0.5 m) from the protocol's start
// to its goal, flown at 3 m/s and scanned at 15 Hz (a frame every 0.2 m), facing along the path.
#pragma once

#include <cmath>
#include <map>
#include <memory>
#include <tuple>
#include <vector>

#include "mmh/sim/forest_world.hpp"
#include "mmh/sim/sensor.hpp"
#include "mmh/sim/shortest_path.hpp"

namespace mmh {

struct FlightScans {
  std::shared_ptr<const sim::ForestWorld> world;
  std::vector<sim::Scan> scans;  // in flight order
};

// Cached per (density, sensor, free_ray_stride). Header-only: used by bench_*.cpp files only.
inline const FlightScans& flightScans(double density_per_m2, sim::SensorKind kind,
                                      int free_ray_stride = 1) {
  static std::map<std::tuple<double, int, int>, FlightScans> cache;
  FlightScans& out = cache[{density_per_m2, static_cast<int>(kind), free_ray_stride}];
  if (out.world) return out;
  ForestSpec spec;
  spec.density_per_m2 = density_per_m2;
  spec.seed = 1;
  out.world = std::make_shared<sim::ForestWorld>(generateForest(spec));
  std::vector<sim::Disc> discs;
  for (const auto& c : out.world->cylinders()) discs.push_back({c.center, c.radius + 0.5});
  std::vector<Eigen::Vector2d> path;
  sim::shortestPathAmongDiscs(discs, spec.start.head<2>(), spec.goal.head<2>(), &path);
  sim::SimParams params;
  params.free_ray_stride = free_ray_stride;
  sim::Sensor sensor(kind, params, 1);
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const Eigen::Vector2d d = path[i + 1] - path[i];
    const double len = d.norm();
    const double yaw = std::atan2(d.y(), d.x());
    for (double s = 0.0; s < len; s += 0.2) {
      const Eigen::Vector2d p = path[i] + d * (s / len);
      sim::Scan scan;
      sensor.scan(*out.world, Eigen::Vector3d(p.x(), p.y(), spec.start.z()),
                  Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())), &scan);
      out.scans.push_back(std::move(scan));
    }
  }
  return out;
}

}  // namespace mmh
