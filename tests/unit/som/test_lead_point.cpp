// The second candidate of a fast start (lead_point.hpp): when it is tried, where its path begins,
// and that SOM's answer with it is never slower than without it.
#include <gtest/gtest.h>

#include "mmh/common/collision_check.hpp"
#include "mmh/common/vehicle_limits.hpp"
#include "mmh/som/lead_point.hpp"
#include "mmh/som/planner.hpp"
#include "som_test_worlds.hpp"

using Eigen::Vector3d;

namespace {

mmh::KinematicState movingAlongX(double speed) {
  mmh::KinematicState s;
  s.position = Vector3d(0.0, 0.0, 1.2);
  s.velocity = Vector3d(speed, 0.0, 0.0);
  return s;
}

const Vector3d kLo(-2, -4, 0.3), kHi(14, 4, 2.7);

}  // namespace

TEST(LeadPoint, OnlyAFastStartWhosePathTurnsAwaySharplyTriesIt) {
  const mmh::som::LeadPointParams p;  // 1 m/s, 45 degrees
  const mmh::KinematicState fast = movingAlongX(3.0);
  EXPECT_FALSE(mmh::som::turnsAwayFromVelocity(fast, Vector3d(5.0, 0.0, 1.2), p));
  EXPECT_FALSE(mmh::som::turnsAwayFromVelocity(fast, Vector3d(5.0, 4.0, 1.2), p));  // 38.7 deg
  EXPECT_TRUE(mmh::som::turnsAwayFromVelocity(fast, Vector3d(5.0, 6.0, 1.2), p));   // 50.2 deg
  EXPECT_TRUE(mmh::som::turnsAwayFromVelocity(fast, Vector3d(-5.0, 0.0, 1.2), p));  // behind
  EXPECT_FALSE(mmh::som::turnsAwayFromVelocity(movingAlongX(0.9), Vector3d(-5.0, 0.0, 1.2), p));
}

TEST(LeadPoint, LiesReachBrakingDistancesAheadOrBeforeTheFirstBlockedCell) {
  const mmh::som::LeadPointParams p;  // reach 1.5
  const mmh::KinematicState s = movingAlongX(3.0);
  const double ahead_m = 1.5 * mmh::stoppingDistance(3.0, 2.0);  // 3.375 m
  const auto open = som_test::makeWorld([](const Vector3d&) { return false; });
  const auto free_lead = mmh::som::leadPoint(*open.grid, s, 2.0, kLo, kHi, p);
  ASSERT_TRUE(free_lead.has_value());
  EXPECT_NEAR(free_lead->x(), ahead_m, 1e-9);
  EXPECT_NEAR(free_lead->y(), 0.0, 1e-9);
  // A wall across the way at x = 2: the point lies before its 0.3 m margin, on a free line.
  const auto wall =
      som_test::makeWorld([](const Vector3d& q) { return std::abs(q.x() - 2.05) < 0.06; });
  const auto walled = mmh::som::leadPoint(*wall.grid, s, 2.0, kLo, kHi, p);
  ASSERT_TRUE(walled.has_value());
  EXPECT_LT(walled->x(), 2.0 - 0.3 + 0.05);
  EXPECT_GE(walled->x(), 0.3);
  EXPECT_TRUE(mmh::isSegmentFree(*wall.grid, s.position, *walled));
  // The geofence ends 2 m ahead: the point stays inside it.
  const auto fenced = mmh::som::leadPoint(*open.grid, s, 2.0, kLo, Vector3d(2.0, 4.0, 2.7), p);
  ASSERT_TRUE(fenced.has_value());
  EXPECT_LE(fenced->x(), 2.0);
  // A wall right ahead (its margin reaches the start's next 0.3 m): none.
  const auto close =
      som_test::makeWorld([](const Vector3d& q) { return std::abs(q.x() - 0.45) < 0.06; });
  EXPECT_FALSE(mmh::som::leadPoint(*close.grid, s, 2.0, kLo, kHi, p).has_value());
  // Reach 0 switches it off.
  mmh::som::LeadPointParams off = p;
  off.reach = 0.0;
  EXPECT_FALSE(mmh::som::leadPoint(*open.grid, s, 2.0, kLo, kHi, off).has_value());
}

TEST(LeadPoint, TheAnswerOfAFastStartTurningBackIsNeverSlowerWithIt) {
  // Flying along +x at 3 m/s with the target behind, past a pillar: the A* path turns back at
  // once; the candidate that first goes on ahead is planned too, and the faster one answered.
  som_test::World w =
      som_test::makeWorld([](const Vector3d& q) { return som_test::inCylinder(q, 1.0, 1.5, 0.4); });
  w.start = Vector3d(2.0, 0.0, 1.2);
  w.target = Vector3d(-1.0, 3.0, 1.2);
  mmh::KinematicState s;
  s.position = w.start;
  s.velocity = Vector3d(3.0, 0.0, 0.0);
  mmh::som::SomParams with;
  with.clearance.cost_cells = 0.0;  // one path per candidate: the lead path alone is under test
  mmh::som::SomParams without = with;
  without.lead.reach = 0.0;
  mmh::som::Planner planner_with(with), planner_without(without);
  const mmh::som::PlanOutput a = planner_with.plan(*w.grid, s, w.target);
  const mmh::som::PlanOutput b = planner_without.plan(*w.grid, s, w.target);
  // Without it, SOM answers nothing here (the turn back leaves its corridor); with it, it does.
  ASSERT_TRUE(a.ok()) << a.detail;
  EXPECT_EQ(a.lead_paths, 1);
  EXPECT_EQ(a.lead_paths_taken, 1);
  EXPECT_EQ(b.lead_paths, 0);
  if (b.ok()) {
    EXPECT_LE(a.trajectory.duration(), b.trajectory.duration() + 1e-9);
  }
  EXPECT_LT((a.trajectory.position(a.trajectory.duration()) - w.target).norm(), 1e-3);
  // Whichever won, the answer keeps out of the obstacle (checked on the raw grid).
  for (double t = 0.0; t <= a.trajectory.duration(); t += 0.005)
    EXPECT_FALSE(w.grid->isOccupiedPoint(a.trajectory.position(t))) << t;
}
