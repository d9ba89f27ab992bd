#include "mmh/som/seed_visibility.hpp"

#include <algorithm>
#include <cmath>

namespace mmh::som {

bool seedBlockedAt(const VoxelGrid& grid, const Eigen::Vector3d& p, const EscapeZone& escape) {
  const Eigen::Vector3i c = grid.localIndexOf(p);
  if (!grid.isBlocked(c)) return false;
  const Eigen::Vector3d centre = grid.centerOfLocal(c);
  return !(escape.radius > 0.0 &&
           (centre - escape.center).squaredNorm() <= escape.radius * escape.radius &&
           escape.frees(grid, c, centre));
}

bool segmentVisible(const VoxelGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                    const EscapeZone& escape, double clearance_m) {
  // A box smaller than a cell touches only the cells that contain its corners.
  const double c = std::clamp(clearance_m, 0.0, 0.499 * grid.resolution());
  const int n =
      std::max(1, static_cast<int>(std::ceil((b - a).norm() / (0.25 * grid.resolution()))));
  for (int i = 0; i <= n; ++i) {
    const Eigen::Vector3d p = a + (b - a) * (static_cast<double>(i) / n);
    if (seedBlockedAt(grid, p, escape)) return false;
    if (c <= 0.0) continue;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d q(p.x() + ((corner & 1) ? c : -c), p.y() + ((corner & 2) ? c : -c),
                              p.z() + ((corner & 4) ? c : -c));
      if (seedBlockedAt(grid, q, escape)) return false;
    }
  }
  return true;
}

bool triangleVisible(const VoxelGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                     const Eigen::Vector3d& c, const EscapeZone& escape, double clearance_m) {
  const int n =
      std::max(1, static_cast<int>(std::ceil((b - a).norm() / (0.5 * grid.resolution()))));
  for (int i = 0; i <= n; ++i)
    if (!segmentVisible(grid, c, a + (b - a) * (static_cast<double>(i) / n), escape, clearance_m))
      return false;
  return true;
}

}  // namespace mmh::som
