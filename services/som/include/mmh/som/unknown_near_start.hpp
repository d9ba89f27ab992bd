// The A* step cost that keeps SOM's path out of unknown space near the vehicle. SOM plans through
// unknown space as if it were free, which is right far ahead: the camera sees it before the
// vehicle gets there. Near the vehicle, unknown space is where the camera has not looked (above
// or below its field of view, beside or behind it, the hidden side of a trunk), and the arbiter
// refuses a trajectory whose stopping reach meets it; an answer through it is flown a few
// tenths of a second and then stopped, and from the stop SOM plans the same way again.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>

#include "mmh/common/voxel_grid.hpp"

namespace mmh::som {

struct UnknownNearStartParams {
  double cost_cells = 10.0;  // extra A* cost of entering such a cell, in cell steps
  double radius_m = 2.5;     // cells whose centres lie within this distance of the start
};

// An AStarOptions::extra_step_cost: cost_cells for an unknown cell of `grid` whose centre lies
// within radius_m of `start`, 0 for any other. Empty (no extra cost) when either parameter is 0.
// `grid` must outlive the returned function.
std::function<double(const Eigen::Vector3i&, int64_t)> unknownNearStartCost(
    const VoxelGrid& grid, const Eigen::Vector3d& start, const UnknownNearStartParams& params);

// The same cells as points, for shortenPath's keep_out: true for a point in an unknown cell whose
// centre lies within radius_m of `start`, other than the start's own cell. Empty when either
// parameter is 0. `grid` must outlive the returned function.
std::function<bool(const Eigen::Vector3d&)> inUnknownNearStart(
    const VoxelGrid& grid, const Eigen::Vector3d& start, const UnknownNearStartParams& params);

}  // namespace mmh::som
