// Saved planning scenarios for benchmarks: forest worlds of the benchmark protocol rasterised
// into fully known map windows, with a start at rest and a target 15 m away.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "mmh/common/forest.hpp"
#include "mmh/common/voxel_grid.hpp"

namespace mmh {

struct PlanningScenario {
  std::shared_ptr<const VoxelGrid> grid;  // inflated by ScenarioSpec::inflation_m
  std::shared_ptr<const std::vector<Cylinder>> forest;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  uint64_t map_seed = 0;
  bool path_exists = false;  // A* on the inflated grid found a path
};

struct ScenarioSpec {
  double density_per_m2 = 0.2;
  int maps = 10;    // distinct forests
  int per_map = 5;  // start/target pairs per forest
  uint64_t seed = 1;
  double target_distance_m = 15.0;
  double altitude_m = 1.2;
  double resolution_m = 0.1;
  double inflation_m = 0.3;
  Eigen::Vector3d window_m = Eigen::Vector3d(32.0, 32.0, 4.0);
};

// maps x per_map scenarios, reproducible from the seed.
std::vector<PlanningScenario> makeForestScenarios(const ScenarioSpec& spec);

}  // namespace mmh
