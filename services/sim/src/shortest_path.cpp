#include "mmh/sim/shortest_path.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "mmh/common/grid_astar.hpp"

namespace mmh::sim {
namespace {

using Eigen::Vector2d;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTwoPi = 2.0 * M_PI;

double wrapAngle(double a) {
  a = std::fmod(a, kTwoPi);
  return a < 0.0 ? a + kTwoPi : a;
}

// Uniform grid of disc indices: a segment only needs the discs registered in the cells it
// crosses (a disc that meets the segment overlaps a cell that contains the meeting point).
class DiscIndex {
 public:
  // The grid covers the discs and the points `extra` (segment end points must lie inside it).
  DiscIndex(const std::vector<Disc>& discs, const std::vector<Vector2d>& extra)
      : discs_(discs), stamp_(discs.size(), 0) {
    if (discs.empty()) return;
    Vector2d lo = Vector2d::Constant(kInf), hi = -lo;
    for (const Vector2d& p : extra) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    double max_r = 0.0;
    for (const Disc& d : discs) {
      lo = lo.cwiseMin(d.center - Vector2d::Constant(d.radius));
      hi = hi.cwiseMax(d.center + Vector2d::Constant(d.radius));
      max_r = std::max(max_r, d.radius);
    }
    cell_ = std::max(1.0, 2.0 * max_r);
    lo_ = lo - Vector2d::Constant(cell_);
    nx_ = static_cast<int>(std::ceil((hi.x() - lo_.x()) / cell_)) + 2;
    ny_ = static_cast<int>(std::ceil((hi.y() - lo_.y()) / cell_)) + 2;
    cells_.resize(static_cast<size_t>(nx_) * ny_);
    for (size_t i = 0; i < discs.size(); ++i) {
      const Disc& d = discs[i];
      const int x0 = cellX(d.center.x() - d.radius), x1 = cellX(d.center.x() + d.radius);
      const int y0 = cellY(d.center.y() - d.radius), y1 = cellY(d.center.y() + d.radius);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) cells_[y * nx_ + x].push_back(static_cast<int>(i));
    }
  }

  // True if the segment p-q does not enter any disc other than skip1/skip2.
  bool segmentFree(const Vector2d& p, const Vector2d& q, int skip1, int skip2) {
    if (discs_.empty()) return true;
    ++generation_;
    bool free = true;
    visitCells(p, q, [&](int cell) {
      for (int i : cells_[cell]) {
        if (stamp_[i] == generation_ || i == skip1 || i == skip2) continue;
        stamp_[i] = generation_;
        if (segmentEntersDisc(p, q, discs_[i])) {
          free = false;
          return false;
        }
      }
      return true;
    });
    return free;
  }

 private:
  static bool segmentEntersDisc(const Vector2d& p, const Vector2d& q, const Disc& d) {
    const Vector2d pq = q - p;
    const double len2 = pq.squaredNorm();
    double t = len2 > 0.0 ? (d.center - p).dot(pq) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    const double dist = (p + t * pq - d.center).norm();
    // Tangent segments touch discs exactly; only a real entry counts.
    return dist < d.radius * (1.0 - 1e-9) - 1e-9;
  }
  int cellX(double x) const {
    return std::clamp(static_cast<int>(std::floor((x - lo_.x()) / cell_)), 0, nx_ - 1);
  }
  int cellY(double y) const {
    return std::clamp(static_cast<int>(std::floor((y - lo_.y()) / cell_)), 0, ny_ - 1);
  }
  // 2-D grid traversal (Amanatides & Woo) of the segment, clamped to the grid.
  template <class F>
  void visitCells(const Vector2d& p, const Vector2d& q, F visit) const {
    int x = cellX(p.x()), y = cellY(p.y());
    const int xe = cellX(q.x()), ye = cellY(q.y());
    const Vector2d d = q - p;
    const int sx = d.x() > 0 ? 1 : -1, sy = d.y() > 0 ? 1 : -1;
    const double inv_x = std::abs(d.x()) > 1e-15 ? 1.0 / std::abs(d.x()) : kInf;
    const double inv_y = std::abs(d.y()) > 1e-15 ? 1.0 / std::abs(d.y()) : kInf;
    const double bx = lo_.x() + (x + (sx > 0 ? 1 : 0)) * cell_;
    const double by = lo_.y() + (y + (sy > 0 ? 1 : 0)) * cell_;
    double tmx = std::isinf(inv_x) ? kInf : std::abs(bx - p.x()) * inv_x;
    double tmy = std::isinf(inv_y) ? kInf : std::abs(by - p.y()) * inv_y;
    const double dtx = cell_ * inv_x, dty = cell_ * inv_y;
    const int max_steps = nx_ + ny_ + 4;
    for (int s = 0; s < max_steps; ++s) {
      if (!visit(y * nx_ + x)) return;
      if (x == xe && y == ye) return;
      if (tmx < tmy) {
        if (tmx > 1.0) return;
        x += sx;
        tmx += dtx;
      } else {
        if (tmy > 1.0) return;
        y += sy;
        tmy += dty;
      }
      if (x < 0 || y < 0 || x >= nx_ || y >= ny_) return;
    }
  }

  const std::vector<Disc>& discs_;
  std::vector<uint32_t> stamp_;
  uint32_t generation_ = 0;
  Vector2d lo_ = Vector2d::Zero();
  double cell_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<int>> cells_;
};

struct Graph {
  struct Node {
    Vector2d p;
    int disc;      // -1 for the end points
    double angle;  // on its disc
  };
  std::vector<Node> nodes;
  std::vector<std::vector<std::pair<int, double>>> adj;
  std::vector<std::vector<int>> on_disc;

  int add(const Vector2d& p, int disc, double angle) {
    nodes.push_back(Node{p, disc, angle});
    adj.emplace_back();
    if (disc >= 0) on_disc[disc].push_back(static_cast<int>(nodes.size()) - 1);
    return static_cast<int>(nodes.size()) - 1;
  }
  void connect(int i, int j, double w) {
    adj[i].emplace_back(j, w);
    adj[j].emplace_back(i, w);
  }
};

// Angular intervals (centre, half width) of circle i that lie inside other discs; `whole` is set
// when another disc covers the entire circle.
std::vector<std::pair<double, double>> blockedArcs(const std::vector<Disc>& discs, int i,
                                                   bool* whole) {
  std::vector<std::pair<double, double>> out;
  *whole = false;
  const Disc& di = discs[i];
  for (size_t j = 0; j < discs.size(); ++j) {
    if (static_cast<int>(j) == i) continue;
    const Disc& dj = discs[j];
    const double d = (dj.center - di.center).norm();
    if (d >= di.radius + dj.radius) continue;  // apart (or touching)
    if (d + di.radius <= dj.radius) {          // circle i inside disc j
      *whole = true;
      return out;
    }
    if (d + dj.radius <= di.radius) continue;  // disc j inside disc i: boundary of i untouched
    const double cos_g =
        (di.radius * di.radius + d * d - dj.radius * dj.radius) / (2.0 * di.radius * d);
    const double g = std::acos(std::clamp(cos_g, -1.0, 1.0));
    const Vector2d v = dj.center - di.center;
    out.emplace_back(std::atan2(v.y(), v.x()), g);
  }
  return out;
}

// True if the counter-clockwise arc from a0 (length span) meets an open blocked interval.
bool arcBlocked(double a0, double span, const std::vector<std::pair<double, double>>& blocked) {
  for (const auto& [centre, half] : blocked) {
    // Interval [centre - half, centre + half] relative to a0, wrapped to [0, 2 pi).
    const double s = wrapAngle(centre - half - a0);
    const double e = s + 2.0 * half;
    const double eps = 1e-9;
    // Overlap of (0, span) with (s, e) or with (s - 2 pi, e - 2 pi).
    if (s < span - eps && e > eps) return true;
    if (e - kTwoPi > eps) return true;
  }
  return false;
}

double solve(const std::vector<Disc>& discs, const Vector2d& a, const Vector2d& b,
             std::vector<Vector2d>* path) {
  DiscIndex index(discs, {a, b});
  if (index.segmentFree(a, b, -1, -1)) {
    if (path) *path = {a, b};
    return (b - a).norm();
  }
  Graph g;
  g.on_disc.resize(discs.size());
  const int na = g.add(a, -1, 0.0), nb = g.add(b, -1, 0.0);
  auto angleOn = [&](int i, const Vector2d& p) {
    const Vector2d v = p - discs[i].center;
    return wrapAngle(std::atan2(v.y(), v.x()));
  };
  // End point to disc tangents.
  for (int end : {na, nb}) {
    const Vector2d p = g.nodes[end].p;
    for (size_t i = 0; i < discs.size(); ++i) {
      const Disc& d = discs[i];
      const Vector2d v = p - d.center;
      const double dist = v.norm();
      if (dist <= d.radius) continue;
      const double theta = std::atan2(v.y(), v.x());
      const double alpha = std::acos(d.radius / dist);
      for (double s : {-1.0, 1.0}) {
        const double phi = theta + s * alpha;
        const Vector2d t = d.center + d.radius * Vector2d(std::cos(phi), std::sin(phi));
        if (!index.segmentFree(p, t, static_cast<int>(i), -1)) continue;
        const int n = g.add(t, static_cast<int>(i), wrapAngle(phi));
        g.connect(end, n, (t - p).norm());
      }
    }
  }
  // Disc to disc bitangents: outer ones (normal at theta +- beta, cos beta = (r1 - r2) / d) and,
  // for discs apart, inner ones (cos beta = (r1 + r2) / d, the second disc on the other side).
  for (size_t i = 0; i < discs.size(); ++i) {
    for (size_t j = i + 1; j < discs.size(); ++j) {
      const Disc &di = discs[i], &dj = discs[j];
      const Vector2d v = dj.center - di.center;
      const double d = v.norm();
      const double theta = std::atan2(v.y(), v.x());
      for (int inner = 0; inner < 2; ++inner) {
        const double c = inner ? (di.radius + dj.radius) / d : (di.radius - dj.radius) / d;
        if (!(std::abs(c) < 1.0)) continue;  // no such tangents (overlap or containment)
        const double beta = std::acos(c);
        for (double s : {-1.0, 1.0}) {
          const double phi = theta + s * beta;
          const Vector2d n(std::cos(phi), std::sin(phi));
          const Vector2d ti = di.center + di.radius * n;
          const Vector2d tj =
              inner ? Vector2d(dj.center - dj.radius * n) : Vector2d(dj.center + dj.radius * n);
          if (!index.segmentFree(ti, tj, static_cast<int>(i), static_cast<int>(j))) continue;
          const int ni = g.add(ti, static_cast<int>(i), angleOn(static_cast<int>(i), ti));
          const int nj = g.add(tj, static_cast<int>(j), angleOn(static_cast<int>(j), tj));
          g.connect(ni, nj, (tj - ti).norm());
        }
      }
    }
  }
  // Free arcs between neighbouring tangent points on each circle.
  for (size_t i = 0; i < discs.size(); ++i) {
    auto& ids = g.on_disc[i];
    if (ids.size() < 2) continue;
    bool whole = false;
    const auto blocked = blockedArcs(discs, static_cast<int>(i), &whole);
    if (whole) continue;
    std::sort(ids.begin(), ids.end(),
              [&](int x, int y) { return g.nodes[x].angle < g.nodes[y].angle; });
    for (size_t k = 0; k < ids.size(); ++k) {
      const int from = ids[k], to = ids[(k + 1) % ids.size()];
      double span = g.nodes[to].angle - g.nodes[from].angle;
      if (k + 1 == ids.size()) span += kTwoPi;
      if (arcBlocked(g.nodes[from].angle, span, blocked)) continue;
      g.connect(from, to, discs[i].radius * span);
    }
  }
  // Dijkstra.
  std::vector<double> dist(g.nodes.size(), kInf);
  std::vector<int> parent(g.nodes.size(), -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
  dist[na] = 0.0;
  open.emplace(0.0, na);
  while (!open.empty()) {
    const auto [du, u] = open.top();
    open.pop();
    if (du > dist[u]) continue;
    if (u == nb) break;
    for (const auto& [v, w] : g.adj[u]) {
      if (du + w < dist[v]) {
        dist[v] = du + w;
        parent[v] = u;
        open.emplace(dist[v], v);
      }
    }
  }
  if (!std::isfinite(dist[nb])) return -1.0;
  if (path) {
    path->clear();
    for (int v = nb; v >= 0; v = parent[v]) path->push_back(g.nodes[v].p);
    std::reverse(path->begin(), path->end());
  }
  return dist[nb];
}

}  // namespace

double shortestPathAmongDiscs(const std::vector<Disc>& discs, const Vector2d& a, const Vector2d& b,
                              std::vector<Vector2d>* path) {
  for (const Disc& d : discs) {
    if ((a - d.center).norm() < d.radius || (b - d.center).norm() < d.radius) return -1.0;
  }
  // A path of length <= bound stays in the ellipse |x - a| + |x - b| <= bound, so discs farther
  // away cannot touch it; grow the bound until the restricted optimum fits inside it.
  double bound = std::max(1.1 * (b - a).norm(), (b - a).norm() + 2.0);
  for (;;) {
    std::vector<Disc> near;
    for (const Disc& d : discs) {
      if ((d.center - a).norm() + (d.center - b).norm() <= bound + 2.0 * d.radius)
        near.push_back(d);
    }
    const double length = solve(near, a, b, path);
    // Fewer obstacles than the full problem: no path here means none at all.
    if (length < 0.0) return -1.0;
    if (length <= bound || near.size() == discs.size()) return length;
    bound = length * (1.0 + 1e-9) + 1e-9;
  }
}

double gridShortestPath(const VoxelGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                        const Eigen::Vector3d& min_bound, const Eigen::Vector3d& max_bound) {
  GridAStar astar;
  AStarOptions options;
  options.unknown_is_free = true;
  options.min_bound = min_bound;
  options.max_bound = max_bound;
  options.max_expansions = std::max<int64_t>(1'000'000, grid.numCells());
  const AStarResult result = astar.search(grid, a, b, options);
  if (!result.ok()) return -1.0;
  return pathLength(shortenPath(grid, result.path));
}

VoxelGrid boundSearchGrid(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double grid_m) {
  double res = grid_m;
  Eigen::Vector3i size;
  for (;;) {
    size = ((hi - lo) / res).array().ceil().cast<int>().max(1).matrix();
    if (static_cast<double>(size.x()) * size.y() * size.z() <= 8e6) break;
    res *= 1.25;
  }
  const Eigen::Vector3i origin((lo / res).array().floor().cast<int>());
  return VoxelGrid(res, origin, size);
}

}  // namespace mmh::sim
