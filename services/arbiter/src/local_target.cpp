#include "mmh/arbiter/local_target.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace mmh::arbiter {

LocalTarget chooseLocalTarget(const VoxelGrid* grid, const Eigen::Vector3d& from,
                              const Eigen::Vector3d& goal, double range_m,
                              const Eigen::Vector3d& fence_min, const Eigen::Vector3d& fence_max,
                              double max_sideways_m) {
  LocalTarget out;
  const Eigen::Vector3d to_goal = goal - from;
  const double dist = to_goal.norm();
  out.is_goal = dist <= range_m;
  Eigen::Vector3d raw = out.is_goal ? goal : Eigen::Vector3d(from + to_goal / dist * range_m);
  raw = raw.cwiseMax(fence_min).cwiseMin(fence_max);
  out.position = raw;
  if (!grid || !grid->isBlockedPoint(raw)) return out;

  out.is_goal = false;
  out.moved = true;
  // Back along the line towards the vehicle: the first free point is the nearest one on the way.
  const double step = grid->resolution();
  const Eigen::Vector3d back = from - raw;
  const double back_len = back.norm();
  for (double s = step; s < back_len; s += step) {
    const Eigen::Vector3d p = raw + back / back_len * s;
    if (!grid->isBlockedPoint(p)) {
      out.position = p;
      return out;
    }
  }
  // Then sideways (horizontally, both sides, growing) around the raw target.
  Eigen::Vector3d side = Eigen::Vector3d::UnitZ().cross(to_goal);
  side = side.norm() > 1e-9 ? Eigen::Vector3d(side.normalized()) : Eigen::Vector3d::UnitY();
  for (double s = step; s <= max_sideways_m; s += step) {
    for (double sign : {1.0, -1.0}) {
      const Eigen::Vector3d p = (raw + sign * s * side).cwiseMax(fence_min).cwiseMin(fence_max);
      if (!grid->isBlockedPoint(p)) {
        out.position = p;
        return out;
      }
    }
  }
  out.found = false;
  return out;
}

}  // namespace mmh::arbiter
