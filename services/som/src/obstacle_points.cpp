#include "mmh/som/obstacle_points.hpp"

#include <algorithm>
#include <cmath>

namespace mmh::som {
namespace {

// Is cell `idx` (with centre `c`) an obstacle for the corridor?
struct BlockedTest {
  const VoxelGrid& grid;
  const EscapeZone& escape;
  bool has_escape;
  double r2;
  bool operator()(int64_t idx, const Eigen::Vector3d& c) const {
    if (!grid.isBlockedLinear(idx)) return false;
    if (!has_escape) return true;
    if ((c - escape.center).squaredNorm() > r2) return true;
    return grid.atLinear(idx) == Occupancy::kOccupied;
  }
};

}  // namespace

bool cellRange(const VoxelGrid& grid, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
               Eigen::Vector3i* first, Eigen::Vector3i* last) {
  const double res = grid.resolution();
  for (int i = 0; i < 3; ++i) {
    const double f = std::ceil(lo[i] / res - 0.5) - grid.originIndex()[i];
    const double l = std::floor(hi[i] / res - 0.5) - grid.originIndex()[i];
    (*first)[i] = static_cast<int>(std::clamp(f, 0.0, double(grid.size()[i])));
    (*last)[i] = static_cast<int>(std::clamp(l, -1.0, double(grid.size()[i] - 1)));
    if ((*first)[i] > (*last)[i]) return false;
  }
  return true;
}

void blockedSurfacePoints(const VoxelGrid& grid, const Eigen::Vector3d& lo,
                          const Eigen::Vector3d& hi, const EscapeZone& escape,
                          std::vector<Eigen::Vector3d>* out) {
  out->clear();
  Eigen::Vector3i f, l;
  if (!cellRange(grid, lo, hi, &f, &l)) return;
  const Eigen::Vector3i& n = grid.size();
  const int64_t sy = n.x(), sz = int64_t{n.x()} * n.y();
  const double res = grid.resolution();
  const Eigen::Vector3d origin = (grid.originIndex().cast<double>().array() + 0.5) * res;
  const BlockedTest blocked{grid, escape, escape.radius > 0.0, escape.radius * escape.radius};
  const bool has_escape = escape.radius > 0.0;
  for (int z = f.z(); z <= l.z(); ++z) {
    const bool z_edge = z == 0 || z == n.z() - 1;
    for (int y = f.y(); y <= l.y(); ++y) {
      const bool yz_edge = z_edge || y == 0 || y == n.y() - 1;
      const int64_t row = grid.linearIndex(Eigen::Vector3i(0, y, z));
      for (int x = f.x(); x <= l.x(); ++x) {
        const int64_t idx = row + x;
        if (!grid.isBlockedLinear(idx)) continue;
        bool surface;
        if (yz_edge || x == 0 || x == n.x() - 1) {
          surface = true;  // a neighbour is outside the window, which counts as not blocked
        } else if (!has_escape) {
          surface = !grid.isBlockedLinear(idx - 1) || !grid.isBlockedLinear(idx + 1) ||
                    !grid.isBlockedLinear(idx - sy) || !grid.isBlockedLinear(idx + sy) ||
                    !grid.isBlockedLinear(idx - sz) || !grid.isBlockedLinear(idx + sz);
        } else {
          const Eigen::Vector3d c = origin + Eigen::Vector3d(x, y, z) * res;
          if (!blocked(idx, c)) continue;
          surface = !blocked(idx - 1, c - Eigen::Vector3d(res, 0, 0)) ||
                    !blocked(idx + 1, c + Eigen::Vector3d(res, 0, 0)) ||
                    !blocked(idx - sy, c - Eigen::Vector3d(0, res, 0)) ||
                    !blocked(idx + sy, c + Eigen::Vector3d(0, res, 0)) ||
                    !blocked(idx - sz, c - Eigen::Vector3d(0, 0, res)) ||
                    !blocked(idx + sz, c + Eigen::Vector3d(0, 0, res));
        }
        if (surface) out->push_back(origin + Eigen::Vector3d(x, y, z) * res);
      }
    }
  }
}

void blockedPointsInside(const VoxelGrid& grid, const Eigen::Vector3d& lo,
                         const Eigen::Vector3d& hi, const Polytope& poly, const EscapeZone& escape,
                         std::vector<Eigen::Vector3d>* out) {
  out->clear();
  Eigen::Vector3i f, l;
  if (!cellRange(grid, lo, hi, &f, &l)) return;
  const double res = grid.resolution();
  const Eigen::Vector3d origin = (grid.originIndex().cast<double>().array() + 0.5) * res;
  const BlockedTest blocked{grid, escape, escape.radius > 0.0, escape.radius * escape.radius};
  for (int z = f.z(); z <= l.z(); ++z) {
    for (int y = f.y(); y <= l.y(); ++y) {
      const Eigen::Vector3d row_start = origin + Eigen::Vector3d(0.0, y, z) * res;
      double t0, t1;
      if (!poly.lineInterval(row_start, 0, &t0, &t1)) continue;
      t0 = std::max(t0, (f.x() - 1) * res);
      t1 = std::min(t1, (l.x() + 1) * res);
      if (t0 > t1) continue;
      // Cells x with centre t = x * res in [t0, t1] (a little wider; the exact test follows).
      const int x0 = std::max(f.x(), static_cast<int>(std::floor(t0 / res)));
      const int x1 = std::min(l.x(), static_cast<int>(std::ceil(t1 / res)));
      const int64_t row = grid.linearIndex(Eigen::Vector3i(0, y, z));
      for (int x = x0; x <= x1; ++x) {
        if (!grid.isBlockedLinear(row + x)) continue;
        const Eigen::Vector3d c = row_start + Eigen::Vector3d(x * res, 0.0, 0.0);
        if (blocked(row + x, c) && poly.maxViolation(c) < 0.0) out->push_back(c);
      }
    }
  }
}

}  // namespace mmh::som
