// The stuck detector's way back along flown positions (retrace.hpp): it passes every point of
// the route, ends at rest at the last, keeps the limits; and the check that it keeps off the
// occupied cells.
#include <gtest/gtest.h>

#include <algorithm>

#include "mmh/arbiter/retrace.hpp"

using Eigen::Vector3d;
using mmh::KinematicState;
using mmh::Trajectory;
using mmh::arbiter::keepsOffOccupied;
using mmh::arbiter::retraceTrajectory;

namespace {

double nearestApproach(const Trajectory& t, const Vector3d& p) {
  double nearest = 1e9;
  for (double s = 0.0; s <= t.duration(); s += 1e-3) {
    nearest = std::min(nearest, (t.position(s) - p).norm());
  }
  return nearest;
}

}  // namespace

TEST(Retrace, PassesTheRouteAndEndsAtRestAtItsLastPointWithinTheLimits) {
  KinematicState start;
  start.position = Vector3d(2.0, 1.0, 1.5);
  start.velocity = Vector3d(0.0, 0.05, 0.0);  // nearly at rest
  const std::vector<Vector3d> route = {start.position,          Vector3d(1.8, 1.0, 1.5),
                                       Vector3d(1.6, 1.0, 1.5), Vector3d(1.6, 0.8, 1.5),
                                       Vector3d(1.6, 0.6, 1.7), Vector3d(1.4, 0.4, 1.7),
                                       Vector3d(1.1, 0.4, 1.6)};
  const auto t = retraceTrajectory(start, route, 0.5, 3.0, 2.0);
  ASSERT_TRUE(t.has_value());
  EXPECT_LT((t->position(0.0) - start.position).norm(), 1e-9);
  EXPECT_LT((t->velocity(0.0) - start.velocity).norm(), 1e-9);
  EXPECT_LT((t->position(t->duration()) - route.back()).norm(), 1e-9);
  EXPECT_LT(t->velocity(t->duration()).norm(), 1e-9);
  // Through every point: each is a waypoint.
  for (const Vector3d& p : route) EXPECT_LT(nearestApproach(*t, p), 2e-3) << p.transpose();
  EXPECT_LE(t->maxSpeed(), 3.0);
  EXPECT_LE(t->maxAcceleration(), 2.0);
  // Slowly: about the asked speed, not the vehicle's limit.
  EXPECT_LT(t->maxSpeed(), 1.0);
  // Tighter limits slow it down further.
  const auto slow = retraceTrajectory(start, route, 0.5, 0.2, 0.3);
  ASSERT_TRUE(slow.has_value());
  EXPECT_LE(slow->maxSpeed(), 0.2);
  EXPECT_LE(slow->maxAcceleration(), 0.3);
  EXPECT_GT(slow->duration(), t->duration());
}

TEST(Retrace, NothingWithoutARouteOfTwoPoints) {
  KinematicState start;
  start.position = Vector3d(0, 0, 1);
  EXPECT_FALSE(retraceTrajectory(start, {}, 0.5, 3.0, 2.0).has_value());
  EXPECT_FALSE(retraceTrajectory(start, {start.position}, 0.5, 3.0, 2.0).has_value());
  // Points within a few centimetres of the start merge into it.
  EXPECT_FALSE(
      retraceTrajectory(start, {start.position, Vector3d(0.01, 0, 1)}, 0.5, 3.0, 2.0).has_value());
}

TEST(Retrace, KeepsOffOccupiedFindsTheSampleNearerThanAllowed) {
  mmh::VoxelGrid grid(0.1, Eigen::Vector3i(-30, -30, 0), Eigen::Vector3i(60, 60, 30));
  for (int64_t i = 0; i < grid.numCells(); ++i) grid.setLinear(i, mmh::Occupancy::kFree);
  grid.set(grid.localIndexOf(Vector3d(0.05, 0.25, 1.05)), mmh::Occupancy::kOccupied);
  KinematicState start;
  start.position = Vector3d(-1.0, 0.0, 1.05);
  const auto t = retraceTrajectory(start, {start.position, Vector3d(1.0, 0.0, 1.05)}, 0.5, 3, 2);
  ASSERT_TRUE(t.has_value());
  // It passes the cell's centre at 0.25 m.
  EXPECT_TRUE(keepsOffOccupied(grid, *t, 0.2, 0.01));
  EXPECT_FALSE(keepsOffOccupied(grid, *t, 0.3, 0.01));
}
