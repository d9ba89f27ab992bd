// The local target of one planning step (paper Sec. III.D.1): on the way to the goal, at most the
// planning range away (past the sensor range on purpose); moved to free space when it falls inside
// a mapped obstacle, so that no mode is asked for the impossible.
#pragma once

#include <Eigen/Core>

#include "mmh/common/voxel_grid.hpp"

namespace mmh::arbiter {

struct LocalTarget {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  bool is_goal = false;  // the goal itself (nearer than the range, and free)
  bool moved = false;    // moved out of an obstacle
  bool found = true;     // false: no free point near the line (the target is then the raw one)
};

// True when no occupied cell centre of `grid` lies within radius_m of p (the planners' notion of
// a free point, whatever inflation the grid itself keeps).
bool isClearOf(const VoxelGrid& grid, const Eigen::Vector3d& p, double radius_m);

// `grid` may be null (no map yet). The target is clamped into [fence_min, fence_max] and, with a
// grid, into its window (window_margin_m inside its faces, where the planners can reach it);
// "free" means isClearOf(grid, p, clearance_m).
LocalTarget chooseLocalTarget(const VoxelGrid* grid, const Eigen::Vector3d& from,
                              const Eigen::Vector3d& goal, double range_m,
                              const Eigen::Vector3d& fence_min, const Eigen::Vector3d& fence_max,
                              double clearance_m, double window_margin_m = 0.5,
                              double max_sideways_m = 2.0);

}  // namespace mmh::arbiter
