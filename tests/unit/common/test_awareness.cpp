#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "mmh/common/awareness.hpp"
#include "mmh/common/forest.hpp"
#include "mmh/common/narrow_space.hpp"

using Eigen::Vector3d;
using Eigen::Vector3i;
using mmh::AwarenessReason;
using mmh::Occupancy;
using mmh::VoxelGrid;

namespace {

// 10 x 10 x 3 m window at 0.1 m, inflation 0.3 m, all free.
VoxelGrid freeGrid() {
  VoxelGrid g(0.1, Vector3i(0, -50, 0), Vector3i(100, 100, 30));
  g.setInflationRadius(0.3);
  for (int64_t i = 0; i < g.numCells(); ++i) g.setLinear(i, Occupancy::kFree);
  return g;
}

void pillar(VoxelGrid& g, double x, double y, double radius) {
  for (int64_t i = 0; i < g.numCells(); ++i) {
    const Vector3d c = g.centerOfLocal(g.localFromLinear(i));
    if (std::hypot(c.x() - x, c.y() - y) <= radius) g.setLinear(i, Occupancy::kOccupied);
  }
}

// The straightforward form of Algorithm 1 (every probe sample looked up with
// VoxelGrid::atPoint): the optimised implementation must give exactly the same answers.
namespace reference {

bool probeHits(const VoxelGrid& grid, const Vector3d& p, const Vector3d& n, double dist) {
  const double step = 0.5 * grid.resolution();
  for (double s = step; s <= dist + 1e-9; s += step) {
    if (grid.isOccupiedPoint(p + s * n)) return true;
  }
  return false;
}

bool bothSidesBlocked(const VoxelGrid& grid, const Vector3d& a, const Vector3d& b, double dist) {
  Vector3d dir = b - a;
  if (dir.norm() < 1e-9) return false;
  dir.normalize();
  Vector3d left = Vector3d::UnitZ().cross(dir);
  if (left.norm() < 1e-6) left = Vector3d::UnitY();
  left.normalize();
  const Vector3d up = dir.cross(left).normalized();
  const Vector3d mid = 0.5 * (a + b);
  if (reference::probeHits(grid, mid, left, dist) && reference::probeHits(grid, mid, -left, dist))
    return true;
  return reference::probeHits(grid, mid, up, dist) && reference::probeHits(grid, mid, -up, dist);
}

mmh::AwarenessResult evaluate(const VoxelGrid& grid, const Vector3d& position, const Vector3d& goal,
                              const mmh::AwarenessParams& params) {
  mmh::AwarenessResult out;
  const Vector3d to_goal = goal - position;
  const double dist = to_goal.norm();
  const double length = std::min(dist, params.sensor_range_m);
  out.ray_end = dist > 1e-9 ? Vector3d(position + to_goal / dist * length) : position;
  const int n = std::max(1, static_cast<int>(std::ceil(length / grid.resolution())));
  auto sample = [&](int i) -> Vector3d {
    return position + (out.ray_end - position) * (static_cast<double>(i) / n);
  };
  for (int i = 1; i <= n; ++i) {
    const Vector3d prev = sample(i - 1), cur = sample(i);
    if (grid.isBlockedPoint(cur)) {
      out.safe = false;
      out.reason = AwarenessReason::kBlocked;
      out.has_blocked_point = true;
      out.first_blocked = cur;
      return out;
    }
    if (reference::bothSidesBlocked(grid, prev, cur, params.narrow_probe_dist_m)) {
      out.safe = false;
      out.reason = AwarenessReason::kNarrow;
      out.has_blocked_point = true;
      out.first_blocked = 0.5 * (prev + cur);
      return out;
    }
  }
  return out;
}

}  // namespace reference

void expectSame(const mmh::AwarenessResult& a, const mmh::AwarenessResult& b,
                const std::string& what) {
  EXPECT_EQ(a.safe, b.safe) << what;
  EXPECT_EQ(a.reason, b.reason) << what;
  EXPECT_EQ(a.has_blocked_point, b.has_blocked_point) << what;
  EXPECT_EQ(a.first_blocked, b.first_blocked) << what;  // bit-identical
  EXPECT_EQ(a.ray_end, b.ray_end) << what;
}

mmh::AwarenessParams params() {
  mmh::AwarenessParams p;
  p.sensor_range_m = 4.5;
  p.narrow_probe_dist_m = 0.8;
  return p;
}

}  // namespace

TEST(Awareness, ClearCorridorIsSafe) {
  VoxelGrid g = freeGrid();
  pillar(g, 3.0, 2.0, 0.3);  // well to the side
  auto r = mmh::evaluateAwareness(g, Vector3d(0.5, 0.0, 1.5), Vector3d(20.0, 0.0, 1.5), params());
  EXPECT_TRUE(r.safe);
  EXPECT_EQ(r.reason, AwarenessReason::kClear);
  EXPECT_TRUE(r.ray_end.isApprox(Vector3d(5.0, 0.0, 1.5)));  // clipped to the sensor range
}

TEST(Awareness, PillarOnTheRayIsBlocked) {
  VoxelGrid g = freeGrid();
  pillar(g, 3.0, 0.0, 0.3);
  auto r = mmh::evaluateAwareness(g, Vector3d(0.5, 0.0, 1.5), Vector3d(20.0, 0.0, 1.5), params());
  EXPECT_FALSE(r.safe);
  EXPECT_EQ(r.reason, AwarenessReason::kBlocked);
  ASSERT_TRUE(r.has_blocked_point);
  // First blocked sample: pillar surface (2.7) minus the 0.3 m inflation, within a voxel.
  EXPECT_NEAR(r.first_blocked.x(), 2.4, 0.15);
}

TEST(Awareness, GapNarrowerThanTwiceTheProbeIsNarrow) {
  VoxelGrid g = freeGrid();
  // Pillars at y = +-1.0 with radius 0.3: free gap of 1.4 m < 2 x 0.8 m; the ray at y = 0 stays
  // out of the inflated zone (0.6 m from each surface).
  pillar(g, 3.0, 1.0, 0.3);
  pillar(g, 3.0, -1.0, 0.3);
  auto r = mmh::evaluateAwareness(g, Vector3d(0.5, 0.0, 1.5), Vector3d(20.0, 0.0, 1.5), params());
  EXPECT_FALSE(r.safe);
  EXPECT_EQ(r.reason, AwarenessReason::kNarrow);
  EXPECT_NEAR(r.first_blocked.x(), 3.0, 0.35);
  // A wider gap (pillars at +-1.5: 2.4 m free) is clear.
  VoxelGrid wide = freeGrid();
  pillar(wide, 3.0, 1.5, 0.3);
  pillar(wide, 3.0, -1.5, 0.3);
  EXPECT_TRUE(
      mmh::evaluateAwareness(wide, Vector3d(0.5, 0, 1.5), Vector3d(20, 0, 1.5), params()).safe);
}

TEST(Awareness, GoalCloserThanRangeStopsTheRayAtTheGoal) {
  VoxelGrid g = freeGrid();
  pillar(g, 4.0, 0.0, 0.3);  // behind the goal
  auto r = mmh::evaluateAwareness(g, Vector3d(0.5, 0.0, 1.5), Vector3d(2.5, 0.0, 1.5), params());
  EXPECT_TRUE(r.safe);
  EXPECT_TRUE(r.ray_end.isApprox(Vector3d(2.5, 0.0, 1.5)));
}

TEST(Awareness, GoalEqualToPositionIsClear) {
  VoxelGrid g = freeGrid();
  auto r = mmh::evaluateAwareness(g, Vector3d(1, 0, 1.5), Vector3d(1, 0, 1.5), params());
  EXPECT_TRUE(r.safe);
  EXPECT_TRUE(r.ray_end.isApprox(Vector3d(1, 0, 1.5)));
}

TEST(Awareness, RayLeavingTheWindowCountsAsFree) {
  VoxelGrid g = freeGrid();
  auto r = mmh::evaluateAwareness(g, Vector3d(8.0, 0.0, 1.5), Vector3d(30.0, 0.0, 1.5), params());
  EXPECT_TRUE(r.safe);
  EXPECT_GT(r.ray_end.x(), g.maxCorner().x());
}

TEST(NarrowSpace, PathThroughGapIsNarrowOpenPathIsNot) {
  VoxelGrid g = freeGrid();
  pillar(g, 3.0, 1.0, 0.3);
  pillar(g, 3.0, -1.0, 0.3);
  std::vector<Vector3d> through{Vector3d(0.5, 0, 1.5), Vector3d(6, 0, 1.5)};
  std::vector<Vector3d> beside{Vector3d(0.5, 4, 1.5), Vector3d(6, 4, 1.5)};
  Vector3d where;
  EXPECT_TRUE(mmh::isPathNarrow(g, through, 0.8, &where));
  EXPECT_NEAR(where.x(), 3.0, 0.4);
  EXPECT_FALSE(mmh::isPathNarrow(g, beside, 0.8));
}

TEST(Awareness, SameAnswersAsTheReferenceOnRandomForests) {
  // Dense forest in a window with negative and positive origin indices; rays in every direction
  // (also climbing and diving, leaving the window), from random points and from points exactly on
  // voxel boundaries, where the point-to-cell rounding matters most.
  int counts[3] = {0, 0, 0};
  for (uint64_t seed : {3u, 4u}) {
    mmh::ForestSpec spec;
    spec.density_per_m2 = 0.25;
    spec.seed = seed;
    const auto forest = mmh::generateForest(spec);
    VoxelGrid g(0.1, Vector3i(-60, -55, -5), Vector3i(120, 110, 35));
    mmh::rasterizeForest(forest, g);
    g.setInflationRadius(0.3);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> ux(-7.0, 7.0), uz(-0.8, 3.8), angle(-M_PI, M_PI);
    std::uniform_int_distribution<int> grid_x(-70, 70), grid_z(-8, 38);
    mmh::AwarenessParams p = params();
    for (int k = 0; k < 3000; ++k) {
      Vector3d from(ux(rng), ux(rng), uz(rng));
      if (k % 3 == 0) from = Vector3d(grid_x(rng), grid_x(rng), grid_z(rng)) * 0.1;
      const double a = angle(rng), climb = (k % 4 == 0) ? 0.5 * angle(rng) : 0.0;
      const double range = (k % 5 == 0) ? 2.0 : 9.0;
      Vector3d to = from + range * Vector3d(std::cos(a), std::sin(a), climb);
      if (k % 7 == 0) to = from + Vector3d(0, 0, k % 2 ? 3.0 : -3.0);  // vertical ray
      p.narrow_probe_dist_m = (k % 2) ? 0.8 : 0.55;
      const auto fast = mmh::evaluateAwareness(g, from, to, p);
      expectSame(fast, reference::evaluate(g, from, to, p), "case " + std::to_string(k));
      ++counts[static_cast<int>(fast.reason)];
    }
  }
  // The cases cover every answer.
  EXPECT_GT(counts[0], 100);
  EXPECT_GT(counts[1], 100);
  EXPECT_GT(counts[2], 50);
}

TEST(NarrowSpace, SameAnswersAsTheReferenceOnVoxelBoundaries) {
  VoxelGrid g = freeGrid();
  pillar(g, 3.0, 0.7, 0.2);
  pillar(g, 3.0, -0.7, 0.2);
  int narrow = 0;
  for (int i = 0; i < 60; ++i) {
    for (int j = -20; j <= 20; ++j) {
      const Vector3d a(0.05 * i, 0.05 * j, 1.5), b = a + Vector3d(0.1, 0.0, 0.0);
      const bool fast = mmh::bothSidesBlocked(g, a, b, 0.8);
      EXPECT_EQ(fast, reference::bothSidesBlocked(g, a, b, 0.8)) << i << " " << j;
      narrow += fast ? 1 : 0;
    }
  }
  EXPECT_GT(narrow, 0);
}

TEST(Awareness, EmptyOrUnknownMapIsClear) {
  VoxelGrid unknown(0.1, Vector3i(0, 0, 0), Vector3i(20, 20, 20));
  auto r = mmh::evaluateAwareness(unknown, Vector3d(0.5, 0.5, 0.5), Vector3d(5, 1, 1), params());
  EXPECT_TRUE(r.safe);
  EXPECT_EQ(r.reason, AwarenessReason::kClear);
  auto none = mmh::evaluateAwareness(VoxelGrid(), Vector3d(0, 0, 0), Vector3d(5, 0, 0), params());
  EXPECT_TRUE(none.safe);
}
