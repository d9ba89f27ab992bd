#include <gtest/gtest.h>

#include "mmh/common/awareness.hpp"
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
