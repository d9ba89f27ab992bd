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

// `grid` may be null (no map yet). The target is clamped into [fence_min, fence_max].
LocalTarget chooseLocalTarget(const VoxelGrid* grid, const Eigen::Vector3d& from,
                              const Eigen::Vector3d& goal, double range_m,
                              const Eigen::Vector3d& fence_min, const Eigen::Vector3d& fence_max,
                              double max_sideways_m = 2.0);

}  // namespace mmh::arbiter
