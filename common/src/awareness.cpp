#include "mmh/common/awareness.hpp"

#include <algorithm>
#include <cmath>

#include "cell_lookup.hpp"
#include "mmh/common/narrow_space.hpp"

namespace mmh {

AwarenessResult evaluateAwareness(const VoxelGrid& grid, const Eigen::Vector3d& position,
                                  const Eigen::Vector3d& goal, const AwarenessParams& params) {
  AwarenessResult out;
  const Eigen::Vector3d to_goal = goal - position;
  const double dist = to_goal.norm();
  const double length = std::min(dist, params.sensor_range_m);
  out.ray_end = dist > 1e-9 ? Eigen::Vector3d(position + to_goal / dist * length) : position;
  // Nothing occupied: no cell is blocked and no probe can hit, the answer is CLEAR.
  if (!grid.valid() || grid.numOccupied() == 0) return out;
  const detail::CellLookup cells(grid);
  const NarrowSpaceProbe narrow(grid, params.narrow_probe_dist_m);
  // SenseRay + discrete(): samples p_0 = P ... p_n = G_M, one voxel apart.
  const int n = std::max(1, static_cast<int>(std::ceil(length / grid.resolution())));
  const Eigen::Vector3d span = out.ray_end - position;
  Eigen::Vector3d prev = position;
  for (int i = 1; i <= n; ++i) {
    const Eigen::Vector3d cur = position + span * (static_cast<double>(i) / n);
    // JudgePointSafe: the current sample of the ray (the vehicle's own cell is not judged: it
    // may lie in the safety margin and that alone is no reason to leave fast mode).
    if (cells.blocked(cur)) {
      out.safe = false;
      out.reason = AwarenessReason::kBlocked;
      out.has_blocked_point = true;
      out.first_blocked = cur;
      return out;
    }
    if (narrow.bothSidesBlocked(prev, cur)) {
      out.safe = false;
      out.reason = AwarenessReason::kNarrow;
      out.has_blocked_point = true;
      out.first_blocked = 0.5 * (prev + cur);
      return out;
    }
    prev = cur;
  }
  return out;
}

}  // namespace mmh
