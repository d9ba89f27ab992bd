#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "mmh/common/collision_check.hpp"
#include "mmh/common/grid_astar.hpp"

using Eigen::Vector3d;
using Eigen::Vector3i;
using mmh::AStarResult;
using mmh::Occupancy;
using mmh::VoxelGrid;

namespace {

// Grid of 1 m cells so that path lengths are easy to count.
VoxelGrid unitGrid(int nx, int ny, int nz) {
  return VoxelGrid(1.0, Vector3i(0, 0, 0), Vector3i(nx, ny, nz));
}
Vector3d cell(int x, int y, int z) {
  return Vector3d(x + 0.5, y + 0.5, z + 0.5);
}

}  // namespace

TEST(GridAStar, StraightAndDiagonalCostsAreOptimal) {
  VoxelGrid g = unitGrid(20, 20, 5);
  mmh::GridAStar astar;
  auto r = astar.search(g, cell(1, 1, 1), cell(11, 1, 1));
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(mmh::pathLength(r.path), 10.0, 1e-9);
  r = astar.search(g, cell(1, 1, 1), cell(8, 5, 3));  // octile: 7 + (sqrt2-1)*4 + (sqrt3-sqrt2)*2
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(mmh::pathLength(r.path), 3 + 2 * std::sqrt(2.0) + 2 * std::sqrt(3.0), 1e-9);
}

TEST(GridAStar, GoesAroundAWallOnTheShortestGridPath) {
  // Wall at x = 5 from y = 0 to y = 7 (full height): the way round is through y = 8.
  VoxelGrid g = unitGrid(11, 12, 1);
  for (int y = 0; y <= 7; ++y) g.set(Vector3i(5, y, 0), Occupancy::kOccupied);
  mmh::GridAStar astar;
  auto r = astar.search(g, cell(2, 2, 0), cell(8, 2, 0));
  ASSERT_TRUE(r.ok());
  // Best 8-connected path: (2,2) -> (5,8) needs 6 up with 3 diagonal: 3 sqrt2 + 3, and back down
  // the same: total 6 sqrt2 + 6.
  EXPECT_NEAR(mmh::pathLength(r.path), 6 * std::sqrt(2.0) + 6, 1e-9);
  for (const auto& p : r.path) EXPECT_FALSE(g.isOccupiedPoint(p));
  for (size_t i = 1; i < r.path.size(); ++i)
    EXPECT_TRUE(mmh::isSegmentFree(g, r.path[i - 1], r.path[i], mmh::CollisionLayer::kOccupied));
}

TEST(GridAStar, FailsClearlyWhenEnclosedOrBlocked) {
  VoxelGrid g = unitGrid(10, 10, 10);
  const Vector3i goal(5, 5, 5);
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (dx || dy || dz) g.set(goal + Vector3i(dx, dy, dz), Occupancy::kOccupied);
  mmh::GridAStar astar;
  auto r = astar.search(g, cell(1, 1, 1), cell(5, 5, 5));
  EXPECT_EQ(r.status, AStarResult::Status::kNoPath);
  EXPECT_TRUE(r.path.empty());
  r = astar.search(g, cell(4, 4, 4), cell(1, 1, 1));
  EXPECT_EQ(r.status, AStarResult::Status::kStartBlocked);
  r = astar.search(g, cell(1, 1, 1), cell(4, 5, 5));
  EXPECT_EQ(r.status, AStarResult::Status::kGoalBlocked);
  r = astar.search(g, cell(1, 1, 1), Vector3d(50, 1, 1));
  EXPECT_EQ(r.status, AStarResult::Status::kOutOfWindow);
  mmh::AStarOptions tight;
  tight.max_expansions = 5;
  r = astar.search(g, cell(0, 0, 0), cell(9, 9, 0), tight);
  EXPECT_EQ(r.status, AStarResult::Status::kBudgetExceeded);
}

TEST(GridAStar, RespectsInflationBoundsAndEscape) {
  VoxelGrid g(0.1, Vector3i(0, 0, 0), Vector3i(60, 40, 20));
  g.setInflationRadius(0.3);
  for (int z = 0; z < 20; ++z)
    for (int y = 0; y < 30; ++y) g.set(Vector3i(30, y, z), Occupancy::kOccupied);
  mmh::GridAStar astar;
  auto r = astar.search(g, Vector3d(1.0, 1.0, 1.0), Vector3d(5.0, 1.0, 1.0));
  ASSERT_TRUE(r.ok());
  for (const auto& p : r.path) EXPECT_FALSE(g.isBlockedPoint(p));
  // Restricting z to a band excludes cells outside it.
  mmh::AStarOptions band;
  band.min_bound = Vector3d(-1e9, -1e9, 0.8);
  band.max_bound = Vector3d(1e9, 1e9, 1.2);
  r = astar.search(g, Vector3d(1.0, 1.0, 1.0), Vector3d(5.0, 1.0, 1.0), band);
  ASSERT_TRUE(r.ok());
  for (const auto& p : r.path) {
    EXPECT_GE(p.z(), 0.8 - 1e-9);
    EXPECT_LE(p.z(), 1.2 + 1e-9);
  }
  // A start inside the margin (0.2 m from the wall) is refused unless escape is allowed.
  const Vector3d near_wall(2.85, 1.0, 1.0);
  EXPECT_EQ(astar.search(g, near_wall, Vector3d(1.0, 1.0, 1.0)).status,
            AStarResult::Status::kStartBlocked);
  mmh::AStarOptions escape;
  escape.start_escape_radius_m = 0.5;
  EXPECT_TRUE(astar.search(g, near_wall, Vector3d(1.0, 1.0, 1.0), escape).ok());
}

TEST(GridAStar, ExtraStepCostSteersThePath) {
  // A straight corridor at y = 2 that costs 5 extra per cell between x = 3 and x = 7: the path
  // takes the detour through y = 4 (4 extra cells of length) instead.
  VoxelGrid g = unitGrid(11, 6, 1);
  mmh::GridAStar astar;
  mmh::AStarOptions o;
  o.extra_step_cost = [](const Vector3i& c, int64_t) {
    return c.y() <= 2 && c.x() >= 3 && c.x() <= 7 ? 5.0 : 0.0;
  };
  auto r = astar.search(g, cell(0, 2, 0), cell(10, 2, 0), o);
  ASSERT_TRUE(r.ok());
  for (const Vector3d& p : r.path) {
    if (p.x() > 3.0 && p.x() < 8.0) {
      EXPECT_GT(p.y(), 3.0);
    }
  }
  r = astar.search(g, cell(0, 2, 0), cell(10, 2, 0));  // without it: straight
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(mmh::pathLength(r.path), 10.0, 1e-9);
}

TEST(ShortenPath, KeepsOnlyTurnPointsAndStaysFree) {
  VoxelGrid g(0.1, Vector3i(0, 0, 0), Vector3i(80, 80, 10));
  g.setInflationRadius(0.2);
  for (int z = 0; z < 10; ++z)
    for (int y = 0; y < 50; ++y) g.set(Vector3i(40, y, z), Occupancy::kOccupied);
  mmh::GridAStar astar;
  auto r = astar.search(g, Vector3d(1.0, 1.0, 0.5), Vector3d(7.0, 1.0, 0.5));
  ASSERT_TRUE(r.ok());
  auto short_path = mmh::shortenPath(g, r.path);
  EXPECT_LT(short_path.size(), 6u);
  EXPECT_GE(short_path.size(), 3u);
  EXPECT_LE(mmh::pathLength(short_path), mmh::pathLength(r.path) + 1e-9);
  for (size_t i = 1; i < short_path.size(); ++i)
    EXPECT_TRUE(mmh::isSegmentFree(g, short_path[i - 1], short_path[i]));
}

TEST(ShortenPath, KeepsShortcutsOutOfTheGivenSpaceButKeepsThePathsOwnSteps) {
  // An L-shaped path in free space: up x = 0.5 to y = 5.5, then along y = 5.5 to x = 5.5.
  VoxelGrid g = unitGrid(8, 8, 1);
  std::vector<Vector3d> path;
  for (int y = 0; y <= 5; ++y) path.push_back(cell(0, y, 0));
  for (int x = 1; x <= 5; ++x) path.push_back(cell(x, 5, 0));
  const auto cut = mmh::shortenPath(g, path);
  ASSERT_EQ(cut.size(), 2u);  // free space: one straight segment

  // Kept out: the inside of the L (x > 1, y < 5) and, on the path itself, the cell (0, 2).
  auto keep_out = [](const Vector3d& p) {
    return (p.x() > 1.0 && p.y() < 5.0) || (p.x() < 1.0 && p.y() > 2.0 && p.y() < 3.0);
  };
  const auto kept = mmh::shortenPath(g, path, keep_out);
  ASSERT_GE(kept.size(), 3u);
  EXPECT_EQ(kept.front(), path.front());
  EXPECT_EQ(kept.back(), path.back());
  for (size_t i = 1; i < kept.size(); ++i) {
    const Vector3d a = kept[i - 1], b = kept[i];
    const bool own_step = (a - b).norm() <= std::sqrt(3.0) + 1e-9;  // neighbouring path points
    for (int k = 0; k <= 100 && !own_step; ++k)
      EXPECT_FALSE(keep_out(a + (b - a) * (k / 100.0))) << "shortcut " << i << " enters it";
  }
  // The corner stays.
  EXPECT_NE(std::find(kept.begin(), kept.end(), cell(0, 5, 0)), kept.end());
}

TEST(GridAStar, WeightedSearchExpandsLessAndStaysWithinItsBound) {
  VoxelGrid g(0.1, Vector3i(0, 0, 0), Vector3i(80, 80, 10));
  g.setInflationRadius(0.2);
  for (int z = 0; z < 10; ++z)
    for (int y = 0; y < 60; ++y) g.set(Vector3i(40, y, z), Occupancy::kOccupied);
  mmh::GridAStar astar;
  const Vector3d a(1.0, 1.0, 0.5), b(7.0, 1.0, 0.5);
  const auto optimal = astar.search(g, a, b);
  mmh::AStarOptions weighted;
  weighted.heuristic_weight = 2.0;
  const auto fast = astar.search(g, a, b, weighted);
  ASSERT_TRUE(optimal.ok());
  ASSERT_TRUE(fast.ok());
  EXPECT_LT(fast.expansions, optimal.expansions);
  EXPECT_LE(mmh::pathLength(fast.path), 2.0 * 1.001 * mmh::pathLength(optimal.path));
  for (size_t i = 1; i < fast.path.size(); ++i)
    EXPECT_TRUE(mmh::isSegmentFree(g, fast.path[i - 1], fast.path[i]));
}

TEST(GridAStar, EscapeFromTheMarginLeadsOutwards) {
  // A wall at x = 3.05 up to y = 2; the start 0.25 m from it, in the margin; the goal beyond the
  // wall's end. With the escape rule no cell of the path but the start's comes nearer to the
  // wall than the start: the path leaves the margin instead of running along the wall in it.
  VoxelGrid g(0.1, Vector3i(0, 0, 0), Vector3i(60, 40, 20));
  g.setInflationRadius(0.3);
  for (int z = 0; z < 20; ++z)
    for (int y = 0; y < 20; ++y) g.set(Vector3i(30, y, z), Occupancy::kOccupied);
  const Vector3d start(2.80, 0.5, 1.0), goal(3.5, 3.5, 1.0);
  ASSERT_TRUE(g.isBlockedPoint(start));
  mmh::AStarOptions escape;
  escape.start_escape_radius_m = 0.5;
  escape.start_escape_min_distance_m = mmh::escapeMinDistance(g, start, 0.28);
  mmh::GridAStar astar;
  const auto r = astar.search(g, start, goal, escape);
  ASSERT_TRUE(r.ok());
  for (size_t i = 1; i + 1 < r.path.size(); ++i) {
    EXPECT_GE(mmh::occupiedDistance(g, r.path[i], 1.0), escape.start_escape_min_distance_m - 1e-9)
        << "path cell " << i << " at " << r.path[i].transpose();
  }
}
