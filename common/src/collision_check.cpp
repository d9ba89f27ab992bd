#include "mmh/common/collision_check.hpp"

#include <algorithm>
#include <cmath>

namespace mmh {

bool isPointBlocked(const VoxelGrid& grid, const Eigen::Vector3d& p, CollisionLayer layer) {
  return layer == CollisionLayer::kInflated ? grid.isBlockedPoint(p) : grid.isOccupiedPoint(p);
}

bool isSegmentFree(const VoxelGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                   CollisionLayer layer,
                   const std::function<bool(const Eigen::Vector3d&)>& also_blocked) {
  const double step = 0.25 * grid.resolution();
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
  for (int i = 0; i <= n; ++i) {
    const Eigen::Vector3d p = a + (b - a) * (static_cast<double>(i) / n);
    if (isPointBlocked(grid, p, layer) || (also_blocked && also_blocked(p))) return false;
  }
  return true;
}

double collisionSampleStep(const VoxelGrid& grid, const Trajectory& traj) {
  return std::max(1e-4, 0.25 * grid.resolution() / std::max(1e-3, traj.maxSpeed()));
}

std::optional<double> firstCollisionTime(const VoxelGrid& grid, const Trajectory& traj, double t0,
                                         double t1, CollisionLayer layer) {
  if (traj.empty()) return std::nullopt;
  t0 = std::max(0.0, t0);
  t1 = std::min(traj.duration(), t1);
  if (t1 < t0) return std::nullopt;
  const double dt = collisionSampleStep(grid, traj);
  for (double t = t0;; t += dt) {
    const double tc = std::min(t, t1);
    if (isPointBlocked(grid, traj.position(tc), layer)) return tc;
    if (tc >= t1) break;
  }
  return std::nullopt;
}

double occupiedDistance(const VoxelGrid& grid, const Eigen::Vector3d& p, double limit_m) {
  if (!(limit_m > 0.0)) return 0.0;
  const double res = grid.resolution();
  const Eigen::Vector3i c = grid.localIndexOf(p);
  const int r = static_cast<int>(std::ceil(limit_m / res)) + 1;
  // The cube of cells round p, clipped to the window once; its rows are contiguous in memory.
  Eigen::Vector3i lo, hi;
  for (int i = 0; i < 3; ++i) {
    lo[i] = std::max(0, c[i] - r);
    hi[i] = std::min(grid.size()[i] - 1, c[i] + r);
  }
  double best2 = limit_m * limit_m;
  for (int z = lo.z(); z <= hi.z(); ++z)
    for (int y = lo.y(); y <= hi.y(); ++y) {
      const int64_t row = grid.linearIndex(Eigen::Vector3i(0, y, z));
      for (int x = lo.x(); x <= hi.x(); ++x) {
        if (grid.atLinear(row + x) != Occupancy::kOccupied) continue;
        best2 = std::min(best2, (grid.centerOfLocal(Eigen::Vector3i(x, y, z)) - p).squaredNorm());
      }
    }
  return std::sqrt(best2);
}

double escapeMinDistance(const VoxelGrid& grid, const Eigen::Vector3d& start, double floor_m) {
  return std::min(floor_m, occupiedDistance(grid, start, floor_m));
}

double escapeZoneEnd(const Trajectory& traj, double radius_m, double step_s) {
  const Eigen::Vector3d start = traj.position(0.0);
  for (double t = 0.0; t < traj.duration(); t += step_s) {
    if ((traj.position(t) - start).norm() > radius_m) return t;
  }
  return traj.duration();
}

std::optional<double> firstEscapeTooDeep(const VoxelGrid& grid, const Trajectory& traj, double t0,
                                         double t1, double step_s, double min_distance_m,
                                         double tolerance_m) {
  for (double t = t0; t < t1; t += step_s) {
    const Eigen::Vector3d p = traj.position(t);
    if (isPointBlocked(grid, p) && !keepsEscapeDistance(grid, p, min_distance_m, tolerance_m))
      return t;
  }
  return std::nullopt;
}

}  // namespace mmh
