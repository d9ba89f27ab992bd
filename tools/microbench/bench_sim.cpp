// Simulator speed: one sensor frame (ray casting with occlusion + points) in a forest of the
// benchmark protocol, from poses along a collision-free flight; and the shortest-path bound.
#include <benchmark/benchmark.h>

#include <random>

#include "mmh/sim/forest_world.hpp"
#include "mmh/sim/sensor.hpp"
#include "mmh/sim/shortest_path.hpp"

namespace {

struct Pose {
  Eigen::Vector3d position;
  Eigen::Quaterniond orientation;
};

// Poses 0.2 m apart along the shortest path (discs inflated by 0.5 m) from start to goal,
// facing along the path.
std::vector<Pose> flightPoses(const mmh::sim::ForestWorld& world, const mmh::ForestSpec& spec) {
  std::vector<mmh::sim::Disc> discs;
  for (const auto& c : world.cylinders()) discs.push_back({c.center, c.radius + 0.5});
  std::vector<Eigen::Vector2d> path;
  mmh::sim::shortestPathAmongDiscs(discs, spec.start.head<2>(), spec.goal.head<2>(), &path);
  std::vector<Pose> poses;
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const Eigen::Vector2d d = path[i + 1] - path[i];
    const double len = d.norm();
    const double yaw = std::atan2(d.y(), d.x());
    for (double s = 0.0; s < len; s += 0.2) {
      const Eigen::Vector2d p = path[i] + d * (s / len);
      poses.push_back(Pose{Eigen::Vector3d(p.x(), p.y(), spec.start.z()),
                           Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()))});
    }
  }
  return poses;
}

void BM_SensorFrame(benchmark::State& state) {
  const bool lidar = state.range(1) != 0;
  mmh::ForestSpec spec;
  spec.density_per_m2 = state.range(0) / 100.0;
  spec.seed = 1;
  const mmh::sim::ForestWorld world = mmh::sim::ForestWorld::generate(spec);
  const auto poses = flightPoses(world, spec);
  mmh::sim::SimParams params;
  mmh::sim::Sensor sensor(lidar ? mmh::sim::SensorKind::kLidar : mmh::sim::SensorKind::kDepth,
                          params, 1);
  mmh::sim::Scan scan;
  size_t i = 0;
  double returns = 0.0;
  for (auto _ : state) {
    const Pose& p = poses[i++ % poses.size()];
    sensor.scan(world, p.position, p.orientation, &scan);
    returns += scan.num_returns;
    benchmark::DoNotOptimize(scan.xyz.data());
  }
  state.counters["rays"] = sensor.numRays();
  state.counters["returns"] = returns / static_cast<double>(state.iterations());
}
// Args: density x 100, lidar (0 = depth camera 160 x 120, 1 = LiDAR 360 x 56).
BENCHMARK(BM_SensorFrame)
    ->Args({0, 0})
    ->Args({10, 0})
    ->Args({20, 0})
    ->Args({20, 1})
    ->Unit(benchmark::kMillisecond);

void BM_ShortestPathBound(benchmark::State& state) {
  mmh::ForestSpec spec;
  spec.density_per_m2 = state.range(0) / 100.0;
  spec.seed = 1;
  const mmh::sim::ForestWorld world = mmh::sim::ForestWorld::generate(spec);
  double length = 0.0;
  for (auto _ : state) {
    length = world.shortestPathLength(spec.start, spec.goal, 0.15);
    benchmark::DoNotOptimize(length);
  }
  state.counters["length_m"] = length;
}
BENCHMARK(BM_ShortestPathBound)->Arg(5)->Arg(10)->Arg(20)->Unit(benchmark::kMillisecond);

}  // namespace
