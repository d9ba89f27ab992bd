#include <gtest/gtest.h>

#include "mmh/arbiter/goal_placement.hpp"
#include "mmh/arbiter/local_target.hpp"

using Eigen::Vector3d;
using Eigen::Vector3i;

namespace {

const Vector3d kFenceMin(-30, -30, 0.3), kFenceMax(30, 30, 2.7);

mmh::VoxelGrid gridWithPillarAt(double x, double y) {
  mmh::VoxelGrid g(0.1, Vector3i(-160, -160, -8), Vector3i(320, 320, 40));
  g.setInflationRadius(0.3);
  for (int64_t i = 0; i < g.numCells(); ++i) {
    const Vector3d c = g.centerOfLocal(g.localFromLinear(i));
    if (std::hypot(c.x() - x, c.y() - y) <= 0.5) g.setLinear(i, mmh::Occupancy::kOccupied);
  }
  return g;
}

}  // namespace

TEST(LocalTarget, RangeLimitedOnTheWayToTheGoal) {
  auto t = mmh::arbiter::chooseLocalTarget(nullptr, Vector3d(0, 0, 1), Vector3d(28, 0, 1), 15.0,
                                           kFenceMin, kFenceMax, 0.3);
  EXPECT_TRUE(t.position.isApprox(Vector3d(15, 0, 1)));
  EXPECT_FALSE(t.is_goal);
  t = mmh::arbiter::chooseLocalTarget(nullptr, Vector3d(0, 0, 1), Vector3d(10, 0, 1), 15.0,
                                      kFenceMin, kFenceMax, 0.3);
  EXPECT_TRUE(t.is_goal);
  EXPECT_TRUE(t.position.isApprox(Vector3d(10, 0, 1)));
  // Clamped into the geofence.
  t = mmh::arbiter::chooseLocalTarget(nullptr, Vector3d(0, 0, 1), Vector3d(5, 0, 9), 15.0,
                                      kFenceMin, kFenceMax, 0.3);
  EXPECT_NEAR(t.position.z(), 2.7, 1e-12);
}

TEST(LocalTarget, TargetInsideAnObstacleMovesBackAlongTheLine) {
  mmh::VoxelGrid g = gridWithPillarAt(10.0, 0.0);
  auto t = mmh::arbiter::chooseLocalTarget(&g, Vector3d(0, 0, 1.2), Vector3d(10, 0, 1.2), 15.0,
                                           kFenceMin, kFenceMax, 0.3);
  EXPECT_TRUE(t.moved);
  EXPECT_FALSE(t.is_goal);
  EXPECT_FALSE(g.isBlockedPoint(t.position));
  EXPECT_NEAR(t.position.y(), 0.0, 1e-9);
  EXPECT_LT(t.position.x(), 10.0 - 0.5 - 0.3 + 0.11);  // just in front of the inflated pillar
  EXPECT_GT(t.position.x(), 10.0 - 0.5 - 0.3 - 0.3);
}

TEST(LocalTarget, StaysInsideTheMapWindowOnTheWayToTheGoal) {
  mmh::VoxelGrid g(0.1, Vector3i(-100, -100, 0), Vector3i(200, 200, 30));  // 20 x 20 x 3 m
  auto t = mmh::arbiter::chooseLocalTarget(&g, Vector3d(0, 0, 1.2), Vector3d(28, 7, 1.2), 15.0,
                                           kFenceMin, kFenceMax, 0.3, 0.5);
  EXPECT_FALSE(t.is_goal);
  EXPECT_NEAR(t.position.x(), 9.5, 1e-9);               // window face at 10 m, 0.5 m margin
  EXPECT_NEAR(t.position.y(), 9.5 * 7.0 / 28.0, 1e-9);  // still on the line to the goal
}

TEST(GoalPlacement, AGoalOnOneOccupiedCellMovesToTheNearestClearCellCentre) {
  mmh::VoxelGrid g(0.1, Vector3i(-20, -20, 0), Vector3i(40, 40, 30));
  const Vector3i cell(20, 20, 12);  // global (0, 0, 12): centre (0.05, 0.05, 1.25)
  g.set(cell, mmh::Occupancy::kOccupied);
  const Vector3d centre = g.centerOfLocal(cell);
  // Clear of 0.3 m means no occupied centre within 0.3 m: the nearest cell centres at integer
  // offsets k with |k| * 0.1 > 0.3 have |k|^2 = 10, e.g. (0, -1, -3), at 0.1 sqrt(10) m; of those
  // the lowest z, then y, then x is chosen.
  const mmh::arbiter::GoalPlacement p =
      mmh::arbiter::placeGoal(g, centre, 0.3, 1.0, kFenceMin, kFenceMax);
  ASSERT_TRUE(p.ok);
  EXPECT_TRUE(p.moved);
  EXPECT_NEAR(p.moved_m, 0.1 * std::sqrt(10.0), 1e-9);
  EXPECT_NEAR((p.position - (centre + Vector3d(0.0, -0.1, -0.3))).norm(), 0.0, 1e-9);
  EXPECT_NE(p.why.find("moved 0.32 m to the nearest free point (0.050, -0.050, 0.950)"),
            std::string::npos)
      << p.why;
  // A clear goal stays where it is; beyond the radius the goal is refused, naming the key.
  const mmh::arbiter::GoalPlacement clear =
      mmh::arbiter::placeGoal(g, centre + Vector3d(0.5, 0, 0), 0.3, 1.0, kFenceMin, kFenceMax);
  EXPECT_TRUE(clear.ok);
  EXPECT_FALSE(clear.moved);
  const mmh::arbiter::GoalPlacement refused =
      mmh::arbiter::placeGoal(g, centre, 0.3, 0.3, kFenceMin, kFenceMax);
  EXPECT_FALSE(refused.ok);
  EXPECT_NE(refused.why.find("arbiter.goal_relocate_radius_m"), std::string::npos);
}

TEST(GoalPlacement, TheMovedGoalStaysInsideTheGeofence) {
  mmh::VoxelGrid g(0.1, Vector3i(-20, -20, 0), Vector3i(40, 40, 30));
  const Vector3i cell(20, 20, 12);
  g.set(cell, mmh::Occupancy::kOccupied);
  const Vector3d centre = g.centerOfLocal(cell);
  // A fence whose floor is the goal's height: the nearest points below it are not allowed.
  const mmh::arbiter::GoalPlacement p = mmh::arbiter::placeGoal(
      g, centre, 0.3, 1.0, Vector3d(-30, -30, centre.z() - 1e-9), kFenceMax);
  ASSERT_TRUE(p.ok);
  EXPECT_GE(p.position.z(), centre.z() - 1e-9);
  EXPECT_NEAR(p.moved_m, 0.1 * std::sqrt(10.0), 1e-9);
}
