// Random forest worlds of the benchmark protocol (docs/benchmark.md): vertical cylinders of random
// diameter at a given density, with the start and goal kept clear. Used by the simulator, the
// planner benchmarks and tests.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "mmh/common/voxel_grid.hpp"

namespace mmh {

struct Cylinder {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 0.3;
  double z_min = 0.0, z_max = 3.0;
};

struct ForestSpec {
  Eigen::Vector3d size_m = Eigen::Vector3d(50.0, 50.0, 3.0);  // world box, centred on x = y = 0
  double density_per_m2 = 0.1;                                // obstacles per square metre
  uint64_t seed = 7;
  Eigen::Vector3d start = Eigen::Vector3d(-19.95, 0.0, 1.2);  // 39.9 m apart, as in the paper
  Eigen::Vector3d goal = Eigen::Vector3d(19.95, 0.0, 1.2);
  double clearance_m = 2.0;  // no obstacle surface closer than this to start or goal (in xy)
  double min_diameter_m = 0.25;
  double max_diameter_m = 1.05;
};

// Exactly round(density * area) cylinders, reproducible from the seed. Throws
// std::invalid_argument when the spec is impossible (negative density, too dense to place).
std::vector<Cylinder> generateForest(const ForestSpec& spec);

// Distance in the xy plane from p to the nearest cylinder surface (negative inside), ignoring
// cylinders whose height range does not contain p.z(). +inf without cylinders.
double distanceToForest(const std::vector<Cylinder>& forest, const Eigen::Vector3d& p);

// Marks every cell of the grid: occupied if its centre is inside a cylinder, free otherwise
// (a fully known map, for planner tests and benchmarks).
void rasterizeForest(const std::vector<Cylinder>& forest, VoxelGrid& grid);

}  // namespace mmh
