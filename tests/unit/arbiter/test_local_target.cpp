#include <gtest/gtest.h>

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
                                           kFenceMin, kFenceMax);
  EXPECT_TRUE(t.position.isApprox(Vector3d(15, 0, 1)));
  EXPECT_FALSE(t.is_goal);
  t = mmh::arbiter::chooseLocalTarget(nullptr, Vector3d(0, 0, 1), Vector3d(10, 0, 1), 15.0,
                                      kFenceMin, kFenceMax);
  EXPECT_TRUE(t.is_goal);
  EXPECT_TRUE(t.position.isApprox(Vector3d(10, 0, 1)));
  // Clamped into the geofence.
  t = mmh::arbiter::chooseLocalTarget(nullptr, Vector3d(0, 0, 1), Vector3d(5, 0, 9), 15.0,
                                      kFenceMin, kFenceMax);
  EXPECT_NEAR(t.position.z(), 2.7, 1e-12);
}

TEST(LocalTarget, TargetInsideAnObstacleMovesBackAlongTheLine) {
  mmh::VoxelGrid g = gridWithPillarAt(10.0, 0.0);
  auto t = mmh::arbiter::chooseLocalTarget(&g, Vector3d(0, 0, 1.2), Vector3d(10, 0, 1.2), 15.0,
                                           kFenceMin, kFenceMax);
  EXPECT_TRUE(t.moved);
  EXPECT_FALSE(t.is_goal);
  EXPECT_FALSE(g.isBlockedPoint(t.position));
  EXPECT_NEAR(t.position.y(), 0.0, 1e-9);
  EXPECT_LT(t.position.x(), 10.0 - 0.5 - 0.3 + 0.11);  // just in front of the inflated pillar
  EXPECT_GT(t.position.x(), 10.0 - 0.5 - 0.3 - 0.3);
}
