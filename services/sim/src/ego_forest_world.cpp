#include "mmh/sim/ego_forest_world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "cell_traversal.hpp"
#include "mmh/common/voxel_grid.hpp"
#include "mmh/sim/shortest_path.hpp"

namespace mmh::sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEdge = kEgoColumnEdgeM;

// Signed distance from p to the box [x0, x1] x [y0, y1] x [0, h]: negative inside.
double distanceToColumn(const Eigen::Vector3d& p, int ix, int iy, double h) {
  const double x0 = ix * kEdge, x1 = (ix + 1) * kEdge;
  const double y0 = iy * kEdge, y1 = (iy + 1) * kEdge;
  const double dx = std::max({x0 - p.x(), 0.0, p.x() - x1});
  const double dy = std::max({y0 - p.y(), 0.0, p.y() - y1});
  const double dz = std::max({0.0 - p.z(), 0.0, p.z() - h});
  if (dx > 0.0 || dy > 0.0 || dz > 0.0) return std::sqrt(dx * dx + dy * dy + dz * dz);
  return -std::min({p.x() - x0, x1 - p.x(), p.y() - y0, y1 - p.y(), p.z(), h - p.z()});
}

}  // namespace

EgoForestWorld::EgoForestWorld(EgoForest forest, const EgoForestBoundOptions& bound)
    : forest_(std::move(forest)), bound_(bound) {
  int x_lo = std::numeric_limits<int>::max(), y_lo = x_lo;
  int x_hi = std::numeric_limits<int>::min(), y_hi = x_hi;
  for (const EgoPillar& pillar : forest_.pillars) {
    for (const EgoColumn& c : pillar.columns) {
      x_lo = std::min(x_lo, c.ix);
      x_hi = std::max(x_hi, c.ix);
      y_lo = std::min(y_lo, c.iy);
      y_hi = std::max(y_hi, c.iy);
    }
  }
  if (x_lo > x_hi) return;  // no column
  ix0_ = x_lo;
  iy0_ = y_lo;
  nx_ = x_hi - x_lo + 1;
  ny_ = y_hi - y_lo + 1;
  heights_.assign(static_cast<size_t>(nx_) * ny_, 0.0);
  // Overlapping pillars: the union of two columns on one cell (both start at z = 0) is the
  // taller one.
  for (const EgoPillar& pillar : forest_.pillars) {
    for (const EgoColumn& c : pillar.columns) {
      double& h = heights_[static_cast<size_t>(c.iy - iy0_) * nx_ + (c.ix - ix0_)];
      if (h == 0.0 && c.height_m > 0.0) ++num_columns_;
      h = std::max(h, c.height_m);
    }
  }
}

double EgoForestWorld::columnHeight(int ix, int iy) const {
  const int x = ix - ix0_, y = iy - iy0_;
  if (x < 0 || y < 0 || x >= nx_ || y >= ny_) return 0.0;
  return heights_[static_cast<size_t>(y) * nx_ + x];
}

double EgoForestWorld::castColumns(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                   double max_range) const {
  if (heights_.empty()) return -1.0;
  // Clip the ray to the height map's footprint, then walk its cells in xy: the columns all stand
  // on z = 0, so a cell's box is hit where the ray's height over the cell meets [0, h].
  double t0 = 0.0, t1 = max_range;
  const double lo[2] = {ix0_ * kEdge, iy0_ * kEdge};
  const double hi[2] = {(ix0_ + nx_) * kEdge, (iy0_ + ny_) * kEdge};
  for (int i = 0; i < 2; ++i) {
    if (std::abs(dir[i]) < 1e-15) {
      if (origin[i] < lo[i] || origin[i] > hi[i]) return -1.0;
      continue;
    }
    double ta = (lo[i] - origin[i]) / dir[i], tb = (hi[i] - origin[i]) / dir[i];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (t0 > t1) return -1.0;
  const Eigen::Vector3d flat_origin(origin.x(), origin.y(), 0.5 * kEdge);
  const Eigen::Vector3d flat_dir(dir.x(), dir.y(), 0.0);
  double hit = -1.0;
  detail::traverseCells(flat_origin, flat_dir, t0, t1, kEdge,
                        [&](const Eigen::Vector3i& cell, double t_in, double t_out) {
                          const double h = columnHeight(cell.x(), cell.y());
                          if (h <= 0.0) return true;
                          const double z_in = origin.z() + t_in * dir.z();
                          if (z_in >= 0.0 && z_in <= h) {
                            hit = t_in;
                            return false;
                          }
                          // Above the column and descending onto its top, or below and rising onto
                          // its bottom.
                          const double z_face = z_in > h ? h : 0.0;
                          if ((z_in > h && dir.z() < 0.0) || (z_in < 0.0 && dir.z() > 0.0)) {
                            const double t = (z_face - origin.z()) / dir.z();
                            if (t <= t_out) {
                              hit = std::max(t, t_in);
                              return false;
                            }
                          }
                          return true;
                        });
  return hit;
}

void EgoForestWorld::raycast(const Eigen::Vector3d& origin,
                             const std::vector<Eigen::Vector3d>& dirs, double max_range,
                             std::vector<double>* ranges) const {
  std::vector<const EllipticRing*> near_rings;
  for (const EllipticRing& ring : forest_.rings) {
    if ((ring.center - origin).norm() - ring.boundingRadius() <= max_range)
      near_rings.push_back(&ring);
  }
  ranges->resize(dirs.size());
  for (size_t r = 0; r < dirs.size(); ++r) {
    double best = castColumns(origin, dirs[r], max_range);
    for (const EllipticRing* ring : near_rings) {
      const double t = rayRing(*ring, origin, dirs[r], best >= 0.0 ? best : max_range);
      if (t >= 0.0 && (best < 0.0 || t < best)) best = t;
    }
    (*ranges)[r] = best;
  }
}

double EgoForestWorld::columnClearance(const Eigen::Vector3d& p) const {
  if (heights_.empty()) return kInf;
  // Search a growing square window: once the nearest column found is within the window's
  // half-width, no column outside it can be nearer.
  for (double half = 0.5;; half *= 2.0) {
    const int x_lo = std::max(ix0_, static_cast<int>(std::floor((p.x() - half) / kEdge)));
    const int x_hi = std::min(ix0_ + nx_ - 1, static_cast<int>(std::floor((p.x() + half) / kEdge)));
    const int y_lo = std::max(iy0_, static_cast<int>(std::floor((p.y() - half) / kEdge)));
    const int y_hi = std::min(iy0_ + ny_ - 1, static_cast<int>(std::floor((p.y() + half) / kEdge)));
    double best = kInf;
    for (int iy = y_lo; iy <= y_hi; ++iy) {
      for (int ix = x_lo; ix <= x_hi; ++ix) {
        const double h = columnHeight(ix, iy);
        if (h > 0.0) best = std::min(best, distanceToColumn(p, ix, iy, h));
      }
    }
    const bool covers_map =
        x_lo <= ix0_ && y_lo <= iy0_ && x_hi >= ix0_ + nx_ - 1 && y_hi >= iy0_ + ny_ - 1;
    if (best <= half || covers_map) return best;
  }
}

double EgoForestWorld::clearance(const Eigen::Vector3d& p) const {
  double best = columnClearance(p);
  for (const EllipticRing& ring : forest_.rings) {
    // The centre distance less the ring's extent is a lower bound: skip rings that cannot win.
    if ((p - ring.center).norm() - ring.boundingRadius() >= best) continue;
    best = std::min(best, distanceToRing(ring, p));
  }
  return best;
}

double EgoForestWorld::shortestPathLength(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          double radius) const {
  // A grid over the corridor around start and goal, clipped to the bound box; coarsened if it
  // would exceed ~8 M cells (the A* keeps 12 bytes per cell).
  const Eigen::Vector3d margin(bound_.corridor_margin_m, bound_.corridor_margin_m, 0.0);
  Eigen::Vector3d lo = a.cwiseMin(b) - margin, hi = a.cwiseMax(b) + margin;
  lo.z() = -kInf;
  hi.z() = kInf;
  lo = lo.cwiseMax(bound_.min_m);
  hi = hi.cwiseMin(bound_.max_m);
  // Without a geofence in z, the columns' tallest top plus room to pass over it.
  double top = 0.0;
  for (double h : heights_) top = std::max(top, h);
  for (const EllipticRing& ring : forest_.rings)
    top = std::max(top, ring.center.z() + ring.boundingRadius());
  lo.z() = std::max(lo.z(), std::min({a.z(), b.z(), 0.0}) - radius);
  hi.z() = std::min(hi.z(), std::max({a.z(), b.z(), top}) + 2.0 * radius + 0.5);
  if ((hi - lo).minCoeff() <= 0.0) return -1.0;
  VoxelGrid grid = boundSearchGrid(lo, hi, bound_.grid_m);
  const double res = grid.resolution();
  const Eigen::Vector3i size = grid.size();
  // A cell is an obstacle where the columns cover its centre (exact on the columns' own grid),
  // or within half a cell of a ring's tube (thinner than a cell, it would fall between centres).
  for (int64_t i = 0; i < grid.numCells(); ++i) {
    const Eigen::Vector3i local = grid.localFromLinear(i);
    const Eigen::Vector3d c = grid.centerOfLocal(local);
    const double h = columnHeight(static_cast<int>(std::floor(c.x() / kEdge)),
                                  static_cast<int>(std::floor(c.y() / kEdge)));
    if (h > 0.0 && c.z() >= 0.0 && c.z() <= h) grid.setLinear(i, Occupancy::kOccupied);
  }
  for (const EllipticRing& ring : forest_.rings) {
    const double r = ring.boundingRadius();
    const Eigen::Vector3i c0 = grid.localIndexOf(ring.center - Eigen::Vector3d::Constant(r));
    const Eigen::Vector3i c1 = grid.localIndexOf(ring.center + Eigen::Vector3d::Constant(r));
    for (int z = std::max(0, c0.z()); z <= std::min(size.z() - 1, c1.z()); ++z)
      for (int y = std::max(0, c0.y()); y <= std::min(size.y() - 1, c1.y()); ++y)
        for (int x = std::max(0, c0.x()); x <= std::min(size.x() - 1, c1.x()); ++x) {
          const Eigen::Vector3i cell(x, y, z);
          if (distanceToRing(ring, grid.centerOfLocal(cell)) <= 0.5 * res)
            grid.set(cell, Occupancy::kOccupied);
        }
  }
  grid.setInflationRadius(radius);
  return gridShortestPath(grid, a, b, lo, hi);
}

std::string EgoForestWorld::describe() const {
  std::ostringstream out;
  out << "ego-forest of " << forest_.pillars.size() << " pillars (" << num_columns_
      << " columns) and " << forest_.rings.size() << " rings";
  return out.str();
}

}  // namespace mmh::sim
