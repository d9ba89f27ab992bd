#include "mmh/sim/forest_world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "mmh/sim/shortest_path.hpp"

namespace mmh::sim {

double rayCylinder(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, const Cylinder& c) {
  const double ox = origin.x() - c.center.x(), oy = origin.y() - c.center.y();
  const double r2 = c.radius * c.radius;
  const double cc = ox * ox + oy * oy - r2;
  const bool inside_xy = cc <= 0.0;
  if (inside_xy && origin.z() >= c.z_min && origin.z() <= c.z_max) return 0.0;
  double best = std::numeric_limits<double>::infinity();
  // Side: |o_xy + t d_xy - c|^2 = r^2, entering root, height inside [z_min, z_max].
  const double a = dir.x() * dir.x() + dir.y() * dir.y();
  if (!inside_xy && a > 1e-14) {
    const double b = 2.0 * (ox * dir.x() + oy * dir.y());
    const double disc = b * b - 4.0 * a * cc;
    if (disc >= 0.0) {
      const double t = (-b - std::sqrt(disc)) / (2.0 * a);
      const double z = origin.z() + t * dir.z();
      if (t >= 0.0 && z >= c.z_min && z <= c.z_max) best = t;
    }
  }
  // Caps.
  if (std::abs(dir.z()) > 1e-14) {
    for (double zc : {c.z_min, c.z_max}) {
      const double t = (zc - origin.z()) / dir.z();
      if (t < 0.0 || t >= best) continue;
      const double px = ox + t * dir.x(), py = oy + t * dir.y();
      if (px * px + py * py <= r2) best = t;
    }
  }
  return std::isfinite(best) ? best : -1.0;
}

namespace {
// Above this many cylinders in the flight band the bound uses a grid instead of the exact graph.
constexpr size_t kMaxExactDiscs = 4000;
}  // namespace

ForestWorld::ForestWorld(std::vector<Cylinder> cylinders) : cylinders_(std::move(cylinders)) {}

void ForestWorld::raycast(const Eigen::Vector3d& origin, const std::vector<Eigen::Vector3d>& dirs,
                          double max_range, std::vector<double>* ranges) const {
  // Candidates: cylinders whose side comes within max_range of the origin in xy, nearest first,
  // filed into azimuth bins by the angle they subtend. A ray only tests the candidates of its
  // bin, and stops once a candidate's xy distance exceeds its best hit (a hit on a cylinder is at
  // least that far away).
  struct Candidate {
    double min_dist;
    const Cylinder* c;
  };
  std::vector<Candidate> candidates;
  for (const Cylinder& c : cylinders_) {
    const double d = (origin.head<2>() - c.center).norm() - c.radius;
    if (d <= max_range) candidates.push_back(Candidate{std::max(0.0, d), &c});
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& x, const Candidate& y) { return x.min_dist < y.min_dist; });
  constexpr int kBins = 720;
  const double bin_width = 2.0 * M_PI / kBins;
  auto binOf = [&](double angle) {
    int b = static_cast<int>(std::floor((angle + M_PI) / bin_width));
    return ((b % kBins) + kBins) % kBins;
  };
  // Bin ranges per candidate, then a compressed (CSR) list of candidates per bin.
  std::vector<std::pair<int, int>> span(candidates.size());
  std::vector<int> count(kBins + 1, 0);
  for (size_t i = 0; i < candidates.size(); ++i) {
    const Cylinder& c = *candidates[i].c;
    const Eigen::Vector2d v = c.center - origin.head<2>();
    const double d = v.norm();
    if (d <= c.radius * 1.000001 + 1e-9) {
      span[i] = {0, kBins - 1};  // around the origin: every direction
    } else {
      const double half = std::asin(std::min(1.0, c.radius / d)) + 1e-9;
      const double az = std::atan2(v.y(), v.x());
      const int b0 = binOf(az - half);
      int b1 = binOf(az + half);
      if (b1 < b0) b1 += kBins;
      span[i] = {b0, std::min(b1, b0 + kBins - 1)};
    }
    for (int b = span[i].first; b <= span[i].second; ++b) ++count[b % kBins + 1];
  }
  for (int b = 0; b < kBins; ++b) count[b + 1] += count[b];
  std::vector<int> fill(count.begin(), count.end() - 1);
  std::vector<int> bins(count[kBins]);
  for (size_t i = 0; i < candidates.size(); ++i) {
    for (int b = span[i].first; b <= span[i].second; ++b)
      bins[fill[b % kBins]++] = static_cast<int>(i);
  }
  ranges->resize(dirs.size());
  for (size_t r = 0; r < dirs.size(); ++r) {
    const Eigen::Vector3d& dir = dirs[r];
    double best = max_range;
    bool hit = false;
    auto test = [&](const Candidate& cand) {
      if (cand.min_dist > best) return false;
      const double t = rayCylinder(origin, dir, *cand.c);
      if (t >= 0.0 && t <= best) {
        best = t;
        hit = true;
      }
      return true;
    };
    if (std::abs(dir.x()) + std::abs(dir.y()) < 1e-12) {
      for (const Candidate& cand : candidates) {
        if (!test(cand)) break;
      }
    } else {
      const int b = binOf(std::atan2(dir.y(), dir.x()));
      for (int k = count[b]; k < count[b + 1]; ++k) {
        if (!test(candidates[bins[k]])) break;
      }
    }
    (*ranges)[r] = hit ? best : -1.0;
  }
}

double ForestWorld::clearance(const Eigen::Vector3d& p) const {
  // Exact distance to the finite cylinders (side, caps and rims), negative inside.
  double best = std::numeric_limits<double>::infinity();
  for (const Cylinder& c : cylinders_) {
    const double radial = (p.head<2>() - c.center).norm() - c.radius;
    const double vertical = std::max(c.z_min - p.z(), p.z() - c.z_max);
    double d;
    if (vertical <= 0.0)
      d = radial <= 0.0 ? std::max(radial, vertical) : radial;
    else
      d = radial <= 0.0 ? vertical : std::hypot(radial, vertical);
    best = std::min(best, d);
  }
  return best;
}

double ForestWorld::shortestPathLength(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       double radius) const {
  // Cylinders that span the flight band block every altitude; the path is planar.
  std::vector<Disc> discs;
  discs.reserve(cylinders_.size());
  const double z_lo = std::min(a.z(), b.z()) - radius, z_hi = std::max(a.z(), b.z()) + radius;
  for (const Cylinder& c : cylinders_) {
    if (c.z_max < z_lo || c.z_min > z_hi) continue;
    discs.push_back(Disc{c.center, c.radius + radius});
  }
  if (discs.size() <= kMaxExactDiscs) {
    const double planar = shortestPathAmongDiscs(discs, a.head<2>(), b.head<2>());
    if (planar < 0.0) return -1.0;
    return std::hypot(planar, b.z() - a.z());
  }
  // Far denser than the protocol's forests: the visibility graph grows with the square of the
  // disc count, so use a planar grid A* (a slab of one cell) instead.
  Eigen::Vector2d lo = a.head<2>().cwiseMin(b.head<2>()), hi = a.head<2>().cwiseMax(b.head<2>());
  for (const Disc& d : discs) {
    lo = lo.cwiseMin(d.center - Eigen::Vector2d::Constant(d.radius));
    hi = hi.cwiseMax(d.center + Eigen::Vector2d::Constant(d.radius));
  }
  const double res = 0.1;
  lo -= Eigen::Vector2d::Constant(1.0);
  hi += Eigen::Vector2d::Constant(1.0);
  const Eigen::Vector3i origin(static_cast<int>(std::floor(lo.x() / res)),
                               static_cast<int>(std::floor(lo.y() / res)), 0);
  const Eigen::Vector3i size(static_cast<int>(std::ceil((hi.x() - lo.x()) / res)) + 1,
                             static_cast<int>(std::ceil((hi.y() - lo.y()) / res)) + 1, 1);
  VoxelGrid grid(res, origin, size);
  for (const Disc& d : discs) {
    const Eigen::Vector3i c0 =
        grid.localIndexOf(Eigen::Vector3d(d.center.x() - d.radius, d.center.y() - d.radius, 0.05));
    const Eigen::Vector3i c1 =
        grid.localIndexOf(Eigen::Vector3d(d.center.x() + d.radius, d.center.y() + d.radius, 0.05));
    for (int y = std::max(0, c0.y()); y <= std::min(size.y() - 1, c1.y()); ++y)
      for (int x = std::max(0, c0.x()); x <= std::min(size.x() - 1, c1.x()); ++x) {
        const Eigen::Vector3i cell(x, y, 0);
        if ((grid.centerOfLocal(cell).head<2>() - d.center).norm() <= d.radius)
          grid.set(cell, Occupancy::kOccupied);
      }
  }
  grid.setInflationRadius(0.0);
  const double planar = gridShortestPath(
      grid, Eigen::Vector3d(a.x(), a.y(), 0.05), Eigen::Vector3d(b.x(), b.y(), 0.05),
      Eigen::Vector3d(lo.x(), lo.y(), 0.0), Eigen::Vector3d(hi.x(), hi.y(), 0.1));
  if (planar < 0.0) return -1.0;
  return std::hypot(planar, b.z() - a.z());
}

std::string ForestWorld::describe() const {
  std::ostringstream out;
  out << "forest of " << cylinders_.size() << " cylinders";
  return out.str();
}

}  // namespace mmh::sim
