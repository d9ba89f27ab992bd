// Where a goal can be flown to: a goal clicked onto a tree (inside a mapped obstacle or within
// the planners' margin of one) would be refused by every mode and the flight would stall next to
// it. It is moved to the nearest point that keeps the margin, within a radius, or refused with
// that reason.
#pragma once

#include <Eigen/Core>
#include <string>

#include "mmh/common/voxel_grid.hpp"

namespace mmh::arbiter {

struct GoalPlacement {
  bool ok = false;     // the goal, or a point near it, is free
  bool moved = false;  // the position differs from the goal asked for
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double moved_m = 0.0;
  std::string why;  // moved or refused: a sentence saying where and why
};

// The goal itself when isClearOf(grid, goal, clearance_m) (nothing mapped within the margin),
// else the nearest cell centre within radius_m of it that is clear and inside the fence (ties:
// the lowest z, then y, then x, so the answer does not depend on the search order), else refused.
GoalPlacement placeGoal(const VoxelGrid& grid, const Eigen::Vector3d& goal, double clearance_m,
                        double radius_m, const Eigen::Vector3d& fence_min,
                        const Eigen::Vector3d& fence_max);

}  // namespace mmh::arbiter
