#include "mmh/arbiter/local_target.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace mmh::arbiter {

bool isClearOf(const VoxelGrid& grid, const Eigen::Vector3d& p, double radius_m) {
  const double res = grid.resolution();
  const Eigen::Vector3i c = grid.localIndexOf(p);
  const int r = static_cast<int>(std::ceil(radius_m / res)) + 1;
  for (int z = -r; z <= r; ++z)
    for (int y = -r; y <= r; ++y)
      for (int x = -r; x <= r; ++x) {
        const Eigen::Vector3i n = c + Eigen::Vector3i(x, y, z);
        // Cell centre to cell centre, as VoxelGrid's inflation measures it.
        if (grid.at(n) == Occupancy::kOccupied &&
            Eigen::Vector3i(x, y, z).cast<double>().norm() * res <= radius_m + 1e-9)
          return false;
      }
  return true;
}

LocalTarget chooseLocalTarget(const VoxelGrid* grid, const Eigen::Vector3d& from,
                              const Eigen::Vector3d& goal, double range_m,
                              const Eigen::Vector3d& fence_min, const Eigen::Vector3d& fence_max,
                              double clearance_m, double window_margin_m, double max_sideways_m) {
  LocalTarget out;
  const Eigen::Vector3d to_goal = goal - from;
  const double dist = to_goal.norm();
  out.is_goal = dist <= range_m;
  Eigen::Vector3d raw = out.is_goal ? goal : Eigen::Vector3d(from + to_goal / dist * range_m);
  Eigen::Vector3d lo = fence_min, hi = fence_max;
  if (grid) {
    lo = lo.cwiseMax(grid->minCorner() + Eigen::Vector3d::Constant(window_margin_m));
    hi = hi.cwiseMin(grid->maxCorner() - Eigen::Vector3d::Constant(window_margin_m));
  }
  if (grid && ((raw.array() < lo.array()).any() || (raw.array() > hi.array()).any())) {
    // Shorten along the way to the goal so that the target stays inside the window.
    double scale = 1.0;
    const Eigen::Vector3d d = raw - from;
    for (int i = 0; i < 3; ++i) {
      if (d[i] > 1e-9 && from[i] + d[i] > hi[i]) scale = std::min(scale, (hi[i] - from[i]) / d[i]);
      if (d[i] < -1e-9 && from[i] + d[i] < lo[i]) scale = std::min(scale, (lo[i] - from[i]) / d[i]);
    }
    raw = from + std::max(0.0, scale) * d;
    out.is_goal = false;
  }
  raw = raw.cwiseMax(lo).cwiseMin(hi);
  out.position = raw;
  auto free = [&](const Eigen::Vector3d& p) { return isClearOf(*grid, p, clearance_m); };
  if (!grid || free(raw)) return out;

  out.is_goal = false;
  out.moved = true;
  // Back along the line towards the vehicle: the first free point is the nearest one on the way.
  const double step = grid->resolution();
  const Eigen::Vector3d back = from - raw;
  const double back_len = back.norm();
  for (double s = step; s < back_len; s += step) {
    const Eigen::Vector3d p = raw + back / back_len * s;
    if (free(p)) {
      out.position = p;
      return out;
    }
  }
  // Then sideways (horizontally, both sides, growing) around the raw target.
  Eigen::Vector3d side = Eigen::Vector3d::UnitZ().cross(to_goal);
  side = side.norm() > 1e-9 ? Eigen::Vector3d(side.normalized()) : Eigen::Vector3d::UnitY();
  for (double s = step; s <= max_sideways_m; s += step) {
    for (double sign : {1.0, -1.0}) {
      const Eigen::Vector3d p = (raw + sign * s * side).cwiseMax(lo).cwiseMin(hi);
      if (free(p)) {
        out.position = p;
        return out;
      }
    }
  }
  out.found = false;
  return out;
}

}  // namespace mmh::arbiter
