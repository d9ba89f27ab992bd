// The stuck detector's memory (progress_monitor.hpp): progress toward the goal and the recently
// flown free space to back off to.
#include <gtest/gtest.h>

#include "mmh/arbiter/local_target.hpp"
#include "mmh/arbiter/progress_monitor.hpp"

using Eigen::Vector3d;
using mmh::arbiter::ProgressMonitor;

namespace {
int64_t at(double s) {
  return static_cast<int64_t>(s * 1e6);
}
}  // namespace

TEST(ProgressMonitor, ProgressIsANewBestDistanceByTheMinimumStep) {
  ProgressMonitor m(0.5, 20.0, 0.2);
  m.restart(at(0));
  m.observe(at(0), Vector3d(0, 0, 1), 10.0);
  m.observe(at(2), Vector3d(0.4, 0, 1), 9.6);  // less than the step: no progress
  EXPECT_NEAR(m.secondsWithoutProgress(at(3)), 3.0, 1e-9);
  m.observe(at(4), Vector3d(1, 0, 1), 9.0);  // progress
  EXPECT_NEAR(m.secondsWithoutProgress(at(5)), 1.0, 1e-9);
  m.observe(at(6), Vector3d(-5, 0, 1), 15.0);  // away from the goal, and back: not progress
  m.observe(at(8), Vector3d(1, 0, 1), 9.0);
  EXPECT_NEAR(m.secondsWithoutProgress(at(8)), 4.0, 1e-9);
  m.restart(at(9));
  EXPECT_NEAR(m.secondsWithoutProgress(at(9)), 0.0, 1e-9);
}

TEST(ProgressMonitor, ADetourOntoNewGroundIsProgressFlyingBackOverItIsNot) {
  // Goal at x = 10; a wall in the way: the vehicle flies sideways along it, then back.
  const Vector3d goal(10, 0, 1);
  ProgressMonitor detour(0.5, 20.0, 0.2, 1.5);
  ProgressMonitor plain(0.5, 20.0, 0.2);
  for (ProgressMonitor* m : {&detour, &plain}) m->restart(at(0));
  double t = 0.0;
  auto fly = [&](const Vector3d& p) {
    for (ProgressMonitor* m : {&detour, &plain}) m->observe(at(t), p, (goal - p).norm());
  };
  for (double y = 0.0; y <= 6.0 + 1e-9; y += 0.5, t += 0.5) fly(Vector3d(0, y, 1));
  // Sideways, ever farther from the goal: only the detour rule sees the new ground (at 1.5 m
  // steps: the last at y = 6, t = 6 s).
  EXPECT_NEAR(detour.secondsWithoutProgress(at(6.0)), 0.0, 1e-9);
  EXPECT_NEAR(plain.secondsWithoutProgress(at(6.0)), 6.0, 1e-9);
  // Back over the same places: no progress for either.
  for (double y = 5.5; y >= 0.0 - 1e-9; y -= 0.5, t += 0.5) fly(Vector3d(0, y, 1));
  EXPECT_NEAR(detour.secondsWithoutProgress(at(t)), t - 6.0, 1e-9);
  // Hovering about one spot (within the step) is not new ground either.
  for (int k = 0; k < 10; ++k, t += 0.5) fly(Vector3d(-0.6 * (k % 2), 0.6 * (k % 3), 1));
  EXPECT_NEAR(detour.secondsWithoutProgress(at(t)), t - 6.0, 1e-9);
  // Past the wall toward the goal: progress again.
  fly(Vector3d(3, 0, 1));
  EXPECT_NEAR(detour.secondsWithoutProgress(at(t)), 0.0, 1e-9);
  // Back the way it came (a back-off) is not new ground, even after that progress.
  const double progress_t = t;
  for (double y = 0.0; y <= 3.0 + 1e-9; y += 0.5) {
    t += 0.5;
    fly(Vector3d(0, y, 1));
  }
  EXPECT_NEAR(detour.secondsWithoutProgress(at(t)), t - progress_t, 1e-9);
  t += 0.5;
  fly(Vector3d(3, 2, 1));  // 2 m from anywhere flown
  EXPECT_NEAR(detour.secondsWithoutProgress(at(t)), 0.0, 1e-9);
  // A new goal starts a new record of places.
  detour.restart(at(t));
  t += 1.0;
  fly(Vector3d(3, 2, 1));
  t += 1.0;
  fly(Vector3d(0, 3, 1));
  EXPECT_NEAR(detour.secondsWithoutProgress(at(t)), 0.0, 1e-9);
}

TEST(ProgressMonitor, BacksOffToTheNewestFlownPointFarEnoughAndClear) {
  mmh::VoxelGrid grid(0.1, Eigen::Vector3i(-50, -50, 0), Eigen::Vector3i(100, 100, 30));
  for (int64_t i = 0; i < grid.numCells(); ++i) grid.setLinear(i, mmh::Occupancy::kFree);
  ProgressMonitor m(0.5, 20.0, 0.2);
  m.restart(at(0));
  for (int k = 0; k <= 40; ++k) m.observe(at(0.1 * k), Vector3d(0.1 * k, 0, 1.5), 10.0);
  // Flown from x = 0 to 4; now at 4. An obstacle next to x = 2.4 .. 2.6.
  for (int64_t i = 0; i < grid.numCells(); ++i) {
    const Vector3d c = grid.centerOfLocal(grid.localFromLinear(i));
    if (std::abs(c.x() - 2.5) < 0.1 && std::abs(c.y() - 0.3) < 0.1) {
      grid.setLinear(i, mmh::Occupancy::kOccupied);
    }
  }
  const auto p = m.backOffPoint(grid, Vector3d(4, 0, 1.5), 1.0, 0.45);
  ASSERT_TRUE(p.has_value());
  EXPECT_NEAR(p->x(), 3.0, 1e-9);  // the newest point at least 1 m back
  // From x = 3.6, the newest point 1 m back lies next to the obstacle: the one before it.
  const auto q = m.backOffPoint(grid, Vector3d(3.6, 0, 1.5), 1.0, 0.45);
  ASSERT_TRUE(q.has_value());
  EXPECT_LT(q->x(), 2.2);
  EXPECT_TRUE(mmh::arbiter::isClearOf(grid, *q, 0.45));
  EXPECT_FALSE(mmh::arbiter::isClearOf(grid, *q + Vector3d(0.2, 0, 0), 0.45));  // next sample
  EXPECT_FALSE(m.backOffPoint(grid, Vector3d(4, 0, 1.5), 10.0, 0.45).has_value());
}

TEST(ProgressMonitor, TheRouteBackIsTheFlownWayNewestFirstEndingAtTheBackOffPoint) {
  mmh::VoxelGrid grid(0.1, Eigen::Vector3i(-50, -50, 0), Eigen::Vector3i(100, 100, 30));
  for (int64_t i = 0; i < grid.numCells(); ++i) grid.setLinear(i, mmh::Occupancy::kFree);
  ProgressMonitor m(0.5, 20.0, 0.05);
  m.restart(at(0));
  // Up 1 m, then 1 m along x, then hovering at (1, 0, 2.5) for 3 s.
  auto tick = [](int k) { return int64_t{50'000} * k; };  // 0.05 s steps, exactly
  for (int k = 0; k <= 20; ++k) m.observe(tick(k), Vector3d(0, 0, 1.5 + 0.05 * k), 10.0);
  for (int k = 1; k <= 20; ++k) m.observe(tick(20 + k), Vector3d(0.05 * k, 0, 2.5), 10.0);
  for (int k = 1; k <= 60; ++k) m.observe(tick(40 + k), Vector3d(1.0, 0, 2.5), 10.0);
  const Vector3d here(1.0, 0.0, 2.5);
  const auto route = m.backOffRoute(grid, here, 1.2, 0.45, 0.2);
  const auto point = m.backOffPoint(grid, here, 1.2, 0.45);
  ASSERT_TRUE(point.has_value());
  ASSERT_GE(route.size(), 3u);
  EXPECT_EQ(route.front(), here);
  EXPECT_EQ(route.back(), *point);
  EXPECT_GE((route.back() - here).norm(), 1.2);
  for (size_t i = 1; i + 1 < route.size(); ++i) {
    EXPECT_GE((route[i] - route[i - 1]).norm(), 0.2 - 1e-9);  // the hover is one point
    EXPECT_LE((route[i] - route[i - 1]).norm(), 0.3 + 1e-6);  // no flown stretch skipped
  }
  // Back along x first, then down: the corner was flown through.
  bool corner = false;
  for (const Vector3d& p : route) corner |= (p - Vector3d(0, 0, 2.5)).norm() < 1e-9;
  EXPECT_TRUE(corner);
  EXPECT_TRUE(m.backOffRoute(grid, here, 10.0, 0.45, 0.2).empty());
}
