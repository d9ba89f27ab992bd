#include "mmh/common/narrow_space.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace mmh {
namespace {

// Occupied cell within dist of p along unit direction n (sampled at half a voxel)?
bool probeHits(const VoxelGrid& grid, const Eigen::Vector3d& p, const Eigen::Vector3d& n,
               double dist) {
  const double step = 0.5 * grid.resolution();
  for (double s = step; s <= dist + 1e-9; s += step) {
    if (grid.isOccupiedPoint(p + s * n)) return true;
  }
  return false;
}

}  // namespace

bool bothSidesBlocked(const VoxelGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                      double probe_dist_m) {
  Eigen::Vector3d dir = b - a;
  if (dir.norm() < 1e-9) return false;
  dir.normalize();
  // Horizontal normal; for a vertical segment any horizontal direction will do.
  Eigen::Vector3d left = Eigen::Vector3d::UnitZ().cross(dir);
  if (left.norm() < 1e-6) left = Eigen::Vector3d::UnitY();
  left.normalize();
  const Eigen::Vector3d up = dir.cross(left).normalized();
  const Eigen::Vector3d mid = 0.5 * (a + b);
  if (probeHits(grid, mid, left, probe_dist_m) && probeHits(grid, mid, -left, probe_dist_m))
    return true;
  return probeHits(grid, mid, up, probe_dist_m) && probeHits(grid, mid, -up, probe_dist_m);
}

bool isPathNarrow(const VoxelGrid& grid, const std::vector<Eigen::Vector3d>& path,
                  double probe_dist_m, Eigen::Vector3d* where) {
  const double step = grid.resolution();
  for (size_t i = 1; i < path.size(); ++i) {
    const Eigen::Vector3d a = path[i - 1], b = path[i];
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d p0 = a + (b - a) * (double(k) / n);
      const Eigen::Vector3d p1 = a + (b - a) * (double(k + 1) / n);
      if (bothSidesBlocked(grid, p0, p1, probe_dist_m)) {
        if (where) *where = 0.5 * (p0 + p1);
        return true;
      }
    }
  }
  return false;
}

}  // namespace mmh
