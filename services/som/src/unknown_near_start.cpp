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

}  // namespace mmh::som
