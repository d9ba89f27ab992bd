#include "mmh/common/forest.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace mmh {

std::vector<Cylinder> generateForest(const ForestSpec& spec) {
  if (!(spec.density_per_m2 >= 0.0) || !(spec.size_m.x() > 0.0) || !(spec.size_m.y() > 0.0) ||
      !(spec.min_diameter_m > 0.0) || spec.max_diameter_m < spec.min_diameter_m) {
    throw std::invalid_argument("forest: density must be >= 0, sizes and diameters positive");
  }
  const double area = spec.size_m.x() * spec.size_m.y();
  const int count = static_cast<int>(std::lround(spec.density_per_m2 * area));
  std::mt19937_64 rng(spec.seed);
  std::uniform_real_distribution<double> ux(-0.5 * spec.size_m.x(), 0.5 * spec.size_m.x());
  std::uniform_real_distribution<double> uy(-0.5 * spec.size_m.y(), 0.5 * spec.size_m.y());
  std::uniform_real_distribution<double> ud(spec.min_diameter_m, spec.max_diameter_m);
  std::vector<Cylinder> forest;
  forest.reserve(count);
  const int max_attempts = 1000 * std::max(1, count);
  int attempts = 0;
  while (static_cast<int>(forest.size()) < count) {
    if (++attempts > max_attempts) {
      throw std::invalid_argument("forest: cannot place " + std::to_string(count) +
                                  " obstacles with the requested clearance");
    }
    Cylinder c;
    c.center = Eigen::Vector2d(ux(rng), uy(rng));
    c.radius = 0.5 * ud(rng);
    c.z_min = 0.0;
    c.z_max = spec.size_m.z();
    const double to_start = (c.center - spec.start.head<2>()).norm() - c.radius;
    const double to_goal = (c.center - spec.goal.head<2>()).norm() - c.radius;
    if (to_start < spec.clearance_m || to_goal < spec.clearance_m) continue;
    forest.push_back(c);
  }
  return forest;
}

double distanceToForest(const std::vector<Cylinder>& forest, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Cylinder& c : forest) {
    if (p.z() < c.z_min || p.z() > c.z_max) continue;
    best = std::min(best, (p.head<2>() - c.center).norm() - c.radius);
  }
  return best;
}

void rasterizeForest(const std::vector<Cylinder>& forest, VoxelGrid& grid) {
  for (int64_t i = 0; i < grid.numCells(); ++i) grid.setLinear(i, Occupancy::kFree);
  const double res = grid.resolution();
  for (const Cylinder& c : forest) {
    // Only the cells in the cylinder's bounding box.
    const Eigen::Vector3i lo = grid.localIndexOf(
        Eigen::Vector3d(c.center.x() - c.radius, c.center.y() - c.radius, c.z_min));
    const Eigen::Vector3i hi = grid.localIndexOf(
        Eigen::Vector3d(c.center.x() + c.radius, c.center.y() + c.radius, c.z_max - 1e-9));
    for (int z = std::max(0, lo.z()); z <= std::min(grid.size().z() - 1, hi.z()); ++z) {
      for (int y = std::max(0, lo.y()); y <= std::min(grid.size().y() - 1, hi.y()); ++y) {
        for (int x = std::max(0, lo.x()); x <= std::min(grid.size().x() - 1, hi.x()); ++x) {
          const Eigen::Vector3i cell(x, y, z);
          const Eigen::Vector3d centre = grid.centerOfLocal(cell);
          if ((centre.head<2>() - c.center).norm() <= c.radius &&
              centre.z() >= c.z_min - 0.5 * res && centre.z() <= c.z_max + 0.5 * res) {
            grid.set(cell, Occupancy::kOccupied);
          }
        }
      }
    }
  }
}

}  // namespace mmh
