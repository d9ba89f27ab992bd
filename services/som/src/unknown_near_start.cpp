#include "mmh/som/unknown_near_start.hpp"

namespace mmh::som {

std::function<double(const Eigen::Vector3i&, int64_t)> unknownNearStartCost(
    const VoxelGrid& grid, const Eigen::Vector3d& start, const UnknownNearStartParams& params) {
  if (params.cost_cells <= 0.0 || params.radius_m <= 0.0) return {};
  const double radius_sq = params.radius_m * params.radius_m;
  const double cost = params.cost_cells;
  return [&grid, start, radius_sq, cost](const Eigen::Vector3i& local, int64_t) {
    if (grid.at(local) != Occupancy::kUnknown) return 0.0;
    return (grid.centerOfLocal(local) - start).squaredNorm() <= radius_sq ? cost : 0.0;
  };
}

std::function<bool(const Eigen::Vector3d&)> inUnknownNearStart(
    const VoxelGrid& grid, const Eigen::Vector3d& start, const UnknownNearStartParams& params) {
  if (params.cost_cells <= 0.0 || params.radius_m <= 0.0) return {};
  const double radius_sq = params.radius_m * params.radius_m;
  const Eigen::Vector3i start_cell = grid.localIndexOf(start);
  return [&grid, start, start_cell, radius_sq](const Eigen::Vector3d& p) {
    const Eigen::Vector3i cell = grid.localIndexOf(p);
    if (cell == start_cell || grid.at(cell) != Occupancy::kUnknown) return false;
    return (grid.centerOfLocal(cell) - start).squaredNorm() <= radius_sq;
  };
}

}  // namespace mmh::som
