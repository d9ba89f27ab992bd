// SOM's A* keeps out of unknown space near the start: the step cost on its own, and the
// planner choosing a way through mapped space over a shorter one through space the camera has
// not looked at. Which way was taken is read from the trajectory, not from the planner.
#include <gtest/gtest.h>

#include "mmh/som/planner.hpp"
#include "mmh/som/unknown_near_start.hpp"
#include "som_test_worlds.hpp"

using Eigen::Vector3d;
using Eigen::Vector3i;
using mmh::Occupancy;

namespace {

// A wall across the window at x = wall_x, 1.9 m high, with a gap at y in [2.4, 3.6]: over the
// wall (z 2.25-2.7 m between its margin and the geofence) is 1.8 m shorter than through the gap.
// The space above the wall, from 1 m before it to 1.5 m after, is unknown.
som_test::World wallWithUnknownTop(double wall_x) {
  auto w = som_test::makeWorld([wall_x](const Vector3d& p) {
    return std::abs(p.x() - wall_x) <= 0.1 && p.z() <= 1.9 && !(p.y() >= 2.4 && p.y() <= 3.6);
  });
  for (int64_t i = 0; i < w.grid->numCells(); ++i) {
    const Vector3d c = w.grid->centerOfLocal(w.grid->localFromLinear(i));
    if (c.z() > 1.9 && c.x() >= wall_x - 1.0 && c.x() <= wall_x + 1.5)
      w.grid->setLinear(i, Occupancy::kUnknown);
  }
  w.grid->setInflationRadius(0.3);
  return w;
}

enum class Way { kOver, kThroughTheGap, kNeither };

// How the trajectory crosses the wall at wall_x.
Way wayAcross(const mmh::Trajectory& t, double wall_x) {
  for (double s = 0.0; s <= t.duration(); s += 1e-3) {
    const Vector3d p = t.position(s);
    if (std::abs(p.x() - wall_x) > 0.05) continue;
    if (p.z() > 2.1) return Way::kOver;
    if (p.y() > 2.4) return Way::kThroughTheGap;
  }
  return Way::kNeither;
}

using som_test::atRest;

}  // namespace

TEST(UnknownNearStart, CostsUnknownCellsWithinTheRadiusOnly) {
  auto w = som_test::makeWorld([](const Vector3d& p) { return p.x() > 5.0 && p.x() < 5.2; });
  mmh::VoxelGrid& g = *w.grid;
  const Vector3d start(0.05, 0.05, 1.25);
  const Vector3i near_unknown = g.localIndexOf(Vector3d(1.05, 0.05, 1.25));
  const Vector3i far_unknown = g.localIndexOf(Vector3d(3.05, 0.05, 1.25));
  const Vector3i near_free = g.localIndexOf(Vector3d(0.55, 0.05, 1.25));
  g.set(near_unknown, Occupancy::kUnknown);
  g.set(far_unknown, Occupancy::kUnknown);
  const auto cost = mmh::som::unknownNearStartCost(g, start, {10.0, 2.5});
  ASSERT_TRUE(cost);
  EXPECT_EQ(cost(near_unknown, g.linearIndex(near_unknown)), 10.0);
  EXPECT_EQ(cost(far_unknown, g.linearIndex(far_unknown)), 0.0);  // 3 m away
  EXPECT_EQ(cost(near_free, g.linearIndex(near_free)), 0.0);
  // Off: no function, A* as before.
  EXPECT_FALSE(mmh::som::unknownNearStartCost(g, start, {0.0, 2.5}));
  EXPECT_FALSE(mmh::som::unknownNearStartCost(g, start, {10.0, 0.0}));
}

TEST(SomPlanner, TakesAMappedWayRatherThanAShorterOneThroughUnknownSpaceNearTheStart) {
  const double wall_x = 1.5;
  const auto w = wallWithUnknownTop(wall_x);
  const auto start = atRest(w.start);

  mmh::som::SomParams unknown_is_free;
  unknown_is_free.unknown_near_start.cost_cells = 0.0;
  const auto over = mmh::som::Planner(unknown_is_free).plan(*w.grid, start, w.target);
  ASSERT_EQ(over.status, mmh::PlanStatus::kOk) << over.detail;
  ASSERT_EQ(wayAcross(over.trajectory, wall_x), Way::kOver);  // the world tests what it should

  const auto around = mmh::som::Planner(mmh::som::SomParams()).plan(*w.grid, start, w.target);
  ASSERT_EQ(around.status, mmh::PlanStatus::kOk) << around.detail;
  EXPECT_EQ(wayAcross(around.trajectory, wall_x), Way::kThroughTheGap);
  for (double s = 0.0; s <= around.trajectory.duration(); s += 1e-3)
    ASSERT_FALSE(w.grid->isOccupiedPoint(around.trajectory.position(s))) << "occupied at " << s;
}

TEST(SomPlanner, PlansThroughUnknownSpaceFartherAhead) {
  // The same wall 4.5 m ahead: the sensor sees over it before the vehicle gets there.
  const double wall_x = 4.5;
  const auto w = wallWithUnknownTop(wall_x);
  const auto start = atRest(w.start);
  const auto out = mmh::som::Planner(mmh::som::SomParams()).plan(*w.grid, start, w.target);
  ASSERT_EQ(out.status, mmh::PlanStatus::kOk) << out.detail;
  EXPECT_EQ(wayAcross(out.trajectory, wall_x), Way::kOver);
}
