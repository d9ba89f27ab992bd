// Goal-oriented spatial awareness (paper Algorithm 1): is the way from the vehicle towards the
// goal, as far as the sensor reaches, free of obstacles and of narrow passages?
#pragma once

#include <Eigen/Core>

#include "mmh/common/voxel_grid.hpp"

namespace mmh {

struct AwarenessParams {
  double sensor_range_m = 4.5;       // r: the sensing ray is clipped to this length
  double narrow_probe_dist_m = 0.8;  // how far BothSideJudge looks to each side
};

enum class AwarenessReason { kClear = 0, kBlocked = 1, kNarrow = 2 };

struct AwarenessResult {
  bool safe = true;  // S
  AwarenessReason reason = AwarenessReason::kClear;
  Eigen::Vector3d ray_end = Eigen::Vector3d::Zero();  // G_M
  bool has_blocked_point = false;
  Eigen::Vector3d first_blocked = Eigen::Vector3d::Zero();
};

// Samples the ray P -> G_M at the grid resolution. The first sample inside the inflated obstacles
// gives BLOCKED; otherwise a narrow pair of consecutive samples gives NARROW; else CLEAR.
// Unknown space, including space outside the window, counts as free.
AwarenessResult evaluateAwareness(const VoxelGrid& grid, const Eigen::Vector3d& position,
                                  const Eigen::Vector3d& goal, const AwarenessParams& params);

}  // namespace mmh
