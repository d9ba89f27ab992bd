// Shortest paths among discs against analytic answers.
#include <gtest/gtest.h>

#include <cmath>
#include <queue>
#include <random>

#include "mmh/common/forest.hpp"
#include "mmh/sim/forest_world.hpp"
#include "mmh/sim/shortest_path.hpp"

using Eigen::Vector2d;
using Eigen::Vector3d;
using mmh::sim::Disc;

TEST(ShortestPath, NoObstaclesIsTheStraightLine) {
  EXPECT_NEAR(mmh::sim::shortestPathAmongDiscs({}, Vector2d(-19.95, 0), Vector2d(19.95, 0)), 39.9,
              1e-12);
  // An empty forest world in 3-D, with a height difference.
  mmh::sim::ForestWorld empty({});
  EXPECT_NEAR(empty.shortestPathLength(Vector3d(0, 0, 1), Vector3d(3, 4, 1), 0.15), 5.0, 1e-12);
  EXPECT_NEAR(empty.shortestPathLength(Vector3d(0, 0, 1), Vector3d(3, 0, 5), 0.15), 5.0, 1e-12);
}

TEST(ShortestPath, AroundOneDiscMatchesTangentsAndArc) {
  // From (-5, 0) to (5, 0) around a unit disc at the origin: two tangents of length sqrt(24)
  // and the arc between the tangent points at angles acos(0.2) and pi - acos(0.2).
  const std::vector<Disc> discs{{Vector2d(0, 0), 1.0}};
  std::vector<Vector2d> path;
  const double length =
      mmh::sim::shortestPathAmongDiscs(discs, Vector2d(-5, 0), Vector2d(5, 0), &path);
  const double expected = 2.0 * std::sqrt(24.0) + (M_PI - 2.0 * std::acos(0.2));
  EXPECT_NEAR(length, expected, 1e-9);
  ASSERT_GE(path.size(), 4u);
  for (const Vector2d& p : path) EXPECT_GE(p.norm(), 1.0 - 1e-9);
  // A disc off the line does not matter.
  const std::vector<Disc> aside{{Vector2d(0, 3), 1.0}};
  EXPECT_NEAR(mmh::sim::shortestPathAmongDiscs(aside, Vector2d(-5, 0), Vector2d(5, 0)), 10.0,
              1e-12);
}

TEST(ShortestPath, OverlappingDiscsActAsOneWall) {
  // Three overlapping discs along y form a wall; the shortest path goes round the outer tangent
  // of the end discs. Check against the analytic answer for going round the top disc alone,
  // which is the binding one (the wall is symmetric, start and goal on the x axis).
  const std::vector<Disc> wall{
      {Vector2d(0, -1.5), 1.0}, {Vector2d(0, 0), 1.0}, {Vector2d(0, 1.5), 1.0}};
  const double length = mmh::sim::shortestPathAmongDiscs(wall, Vector2d(-5, 0), Vector2d(5, 0));
  // Around the disc at (0, 1.5): tangents from (+-5, 0) to a unit disc at distance d.
  const double d = std::hypot(5.0, 1.5);
  const double tangent = std::sqrt(d * d - 1.0);
  // Angle at the disc centre between the two tangent points.
  const double to_start = std::atan2(-1.5, -5.0), to_goal = std::atan2(-1.5, 5.0);
  const double alpha = std::acos(1.0 / d);
  const double a_start = to_start - alpha;  // tangent point seen from the start, upper side
  const double a_goal = to_goal + alpha;
  double arc = a_start - a_goal;  // clockwise over the top
  while (arc < 0) arc += 2 * M_PI;
  while (arc > 2 * M_PI) arc -= 2 * M_PI;
  EXPECT_NEAR(length, 2.0 * tangent + arc, 1e-9);
}

TEST(ShortestPath, EnclosedOrInsideHasNoPath) {
  std::vector<Disc> ring;
  for (int k = 0; k < 24; ++k) {
    const double a = 2 * M_PI * k / 24;
    ring.push_back({Vector2d(3 * std::cos(a), 3 * std::sin(a)), 0.6});
  }
  EXPECT_LT(mmh::sim::shortestPathAmongDiscs(ring, Vector2d(0, 0), Vector2d(10, 0)), 0.0);
  EXPECT_LT(
      mmh::sim::shortestPathAmongDiscs({{Vector2d(0, 0), 1.0}}, Vector2d(0.5, 0), Vector2d(10, 0)),
      0.0);
}

// Brute force: a fine 8-connected grid search in free space gives an upper-bound-like estimate;
// the exact length must not exceed it (plus discretisation) and must not be below the straight
// line. The returned tangent points must be outside every disc and consecutive points must be
// joined either by a free segment or by an arc of one disc.
TEST(ShortestPath, RandomForestsAgreeWithGridSearch) {
  for (int trial = 0; trial < 3; ++trial) {
    mmh::ForestSpec spec;
    spec.size_m = Vector3d(12, 12, 3);
    spec.density_per_m2 = 0.2;
    spec.seed = 100 + trial;
    spec.start = Vector3d(-5, 0, 1);
    spec.goal = Vector3d(5, 0, 1);
    const auto forest = mmh::generateForest(spec);
    std::vector<Disc> discs;
    for (const auto& c : forest) discs.push_back({c.center, c.radius + 0.15});
    std::vector<Vector2d> path;
    const double exact =
        mmh::sim::shortestPathAmongDiscs(discs, Vector2d(-5, 0), Vector2d(5, 0), &path);
    ASSERT_GT(exact, 0.0);
    EXPECT_GE(exact, 10.0 - 1e-9);
    for (const Vector2d& p : path) {
      for (const Disc& d : discs) EXPECT_GE((p - d.center).norm(), d.radius - 1e-6);
    }
    // Grid Dijkstra at 2 cm with 16 neighbour directions over the 14 x 14 m square.
    const double h = 0.02;
    const int n = 700;
    auto blocked = [&](const Vector2d& p) {
      for (const Disc& d : discs)
        if ((p - d.center).norm() < d.radius) return true;
      return false;
    };
    std::vector<double> dist(n * n, 1e18);
    std::vector<char> bad(n * n);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) bad[y * n + x] = blocked(Vector2d(-7 + x * h, -7 + y * h));
    auto idx = [&](const Vector2d& p) {
      return static_cast<int>(std::lround((p.y() + 7) / h)) * n +
             static_cast<int>(std::lround((p.x() + 7) / h));
    };
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
    const int s = idx(Vector2d(-5, 0)), g = idx(Vector2d(5, 0));
    dist[s] = 0;
    open.emplace(0.0, s);
    const int moves[16][2] = {{1, 0},  {-1, 0},  {0, 1},  {0, -1}, {1, 1},  {1, -1},
                              {-1, 1}, {-1, -1}, {2, 1},  {2, -1}, {-2, 1}, {-2, -1},
                              {1, 2},  {1, -2},  {-1, 2}, {-1, -2}};
    while (!open.empty()) {
      auto [du, u] = open.top();
      open.pop();
      if (u == g) break;
      if (du > dist[u]) continue;
      const int ux = u % n, uy = u / n;
      for (const auto& m : moves) {
        const int vx = ux + m[0], vy = uy + m[1];
        if (vx < 0 || vy < 0 || vx >= n || vy >= n) continue;
        const int v = vy * n + vx;
        if (bad[v] || bad[(uy + vy) / 2 * n + (ux + vx) / 2]) continue;
        const double w = h * std::hypot(m[0], m[1]);
        if (du + w < dist[v]) {
          dist[v] = du + w;
          open.emplace(dist[v], v);
        }
      }
    }
    ASSERT_LT(dist[g], 1e17);
    // 16-connectivity overestimates straight runs by at most ~2.7 %; the grid cannot be shorter
    // than the exact answer by more than its cell size around each obstacle it grazes.
    EXPECT_LE(exact, dist[g] + 0.02) << "trial " << trial;
    EXPECT_GE(exact, dist[g] / 1.03 - 0.1) << "trial " << trial;
  }
}
