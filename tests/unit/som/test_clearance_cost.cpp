// SOM's A* keeps away from the inflated obstacles where a wider way is not much longer: the step
// cost against hand-computed clearances, and the path and the trajectory choosing a wide gap
// over a narrow one on the straight line. Which gap was taken is read from the path and the
// trajectory, not from the planner.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include <limits>
#include <string>
#include <vector>

#include "mmh/common/grid_astar.hpp"
#include "mmh/som/clearance_cost.hpp"
#include "mmh/som/planner.hpp"
#include "som_test_worlds.hpp"

using Eigen::Vector3d;
using Eigen::Vector3i;
using mmh::som::ClearanceCost;
using mmh::som::ClearanceCostParams;

namespace {

// A wall across the window at x = 5 (0.4 m thick) with a narrow gap on the straight line,
// y in [-0.4, 0.4] (0.2 m free between the 0.3 m margins), and a wide one, y in [1.6, 3.6].
som_test::World wallWithNarrowAndWideGaps() {
  return som_test::makeWorld([](const Vector3d& p) {
    const bool narrow_gap = std::abs(p.y()) <= 0.4;
    const bool wide_gap = p.y() >= 1.6 && p.y() <= 3.6;
    return std::abs(p.x() - 5.0) <= 0.2 && !narrow_gap && !wide_gap;
  });
}

enum class Gap { kNarrow, kWide, kNeither };

Gap gapAt(const Vector3d& p) {
  if (std::abs(p.y()) <= 0.4) return Gap::kNarrow;
  if (p.y() >= 1.6 && p.y() <= 3.6) return Gap::kWide;
  return Gap::kNeither;
}

// The gap a polyline crosses x = 5 through.
Gap gapOfPath(const std::vector<Vector3d>& path) {
  for (size_t i = 1; i < path.size(); ++i) {
    const Vector3d a = path[i - 1], b = path[i];
    if ((a.x() - 5.0) * (b.x() - 5.0) > 0.0 || a.x() == b.x()) continue;
    return gapAt(a + (b - a) * ((5.0 - a.x()) / (b.x() - a.x())));
  }
  return Gap::kNeither;
}

Gap gapOfTrajectory(const mmh::Trajectory& t) {
  for (double s = 0.0; s <= t.duration(); s += 1e-3) {
    const Vector3d p = t.position(s);
    if (std::abs(p.x() - 5.0) <= 0.01) return gapAt(p);
  }
  return Gap::kNeither;
}

}  // namespace

TEST(ClearanceCost, FallsLinearlyWithTheClearanceToTheInflatedObstacles) {
  // One occupied cell, centred at (0.05, 0.05, 1.25).
  const Vector3d occupied(0.05, 0.05, 1.25);
  auto w = som_test::makeWorld([&](const Vector3d& p) { return (p - occupied).norm() < 0.01; });
  const mmh::VoxelGrid& g = *w.grid;
  const ClearanceCostParams params{10.0, 0.3};
  const Vector3d far_start(-1.9, 3.9, 1.25);  // 2.5 m and more from every cell below
  auto at = [&](double x) { return g.localIndexOf(occupied + Vector3d(x, 0.0, 0.0)); };
  // Along +x the cells up to 0.3 m from it are blocked; the next one's centre lies half a cell
  // off the blocked one's face.
  ASSERT_TRUE(g.isBlocked(at(0.3)));
  ASSERT_FALSE(g.isBlocked(at(0.4)));
  EXPECT_NEAR(ClearanceCost::cellCost(g, at(0.4), params), 10.0 * (1.0 - 0.05 / 0.3), 1e-9);
  EXPECT_NEAR(ClearanceCost::cellCost(g, at(0.5), params), 10.0 * (1.0 - 0.15 / 0.3), 1e-9);
  EXPECT_NEAR(ClearanceCost::cellCost(g, at(0.6), params), 10.0 * (1.0 - 0.25 / 0.3), 1e-9);
  EXPECT_EQ(ClearanceCost::cellCost(g, at(0.7), params), 0.0);
  EXPECT_EQ(ClearanceCost::cellCost(g, at(2.0), params), 0.0);

  // The memoised step cost gives the same, up to its 1/255 steps, on a second grid too.
  ClearanceCost memo;
  for (int round = 0; round < 2; ++round) {
    const auto cost = memo.forGrid(g, far_start, params);
    ASSERT_TRUE(cost);
    for (double x : {0.4, 0.5, 0.6, 0.7, 2.0})
      EXPECT_NEAR(cost(at(x), g.linearIndex(at(x))), ClearanceCost::cellCost(g, at(x), params),
                  10.0 / 255.0);
  }
  // Nothing within free_radius_m of the start.
  const auto near_start = memo.forGrid(g, occupied - Vector3d(2.0, 0.0, 0.0), params);
  EXPECT_EQ(near_start(at(0.4), g.linearIndex(at(0.4))), 0.0);  // 2.4 m from the start
  EXPECT_GT(near_start(at(0.6), g.linearIndex(at(0.6))), 0.0);  // 2.6 m
  // Off: no function, A* as before.
  EXPECT_FALSE(memo.forGrid(g, far_start, {0.0, 0.3}));
  EXPECT_FALSE(memo.forGrid(g, far_start, {10.0, 0.0}));
}

TEST(ClearanceCost, LeadsTheSearchThroughAWideGapRatherThanANarrowOneOnTheStraightLine) {
  const auto w = wallWithNarrowAndWideGaps();
  mmh::GridAStar astar;
  mmh::AStarOptions options;
  const auto straight = astar.search(*w.grid, w.start, w.target, options);
  ASSERT_TRUE(straight.ok());
  ASSERT_EQ(gapOfPath(straight.path), Gap::kNarrow);  // the world tests what it should

  ClearanceCost clearance;
  options.extra_step_cost = clearance.forGrid(*w.grid, w.start, {10.0, 0.3});
  const auto wide = astar.search(*w.grid, w.start, w.target, options);
  ASSERT_TRUE(wide.ok());
  EXPECT_EQ(gapOfPath(wide.path), Gap::kWide);
}

TEST(SomPlanner, FliesThroughTheWideGapWithTheClearanceCost) {
  const auto w = wallWithNarrowAndWideGaps();
  const auto start = som_test::atRest(w.start);
  mmh::som::SomParams params;
  params.clearance = {10.0, 0.3, 2.5, false};  // the path that keeps clear preferred
  const auto out = mmh::som::Planner(params).plan(*w.grid, start, w.target);
  ASSERT_EQ(out.status, mmh::PlanStatus::kOk) << out.detail;
  EXPECT_EQ(gapOfTrajectory(out.trajectory), Gap::kWide);
  for (double s = 0.0; s <= out.trajectory.duration(); s += 1e-3)
    ASSERT_FALSE(w.grid->isBlockedPoint(out.trajectory.position(s))) << "blocked at " << s;
}

TEST(SomPlanner, FallsBackToTheShortestPathWhenAFastStartCannotTurnToTheWideGap) {
  // 3 m before the wall at 3 m/s straight at the narrow gap: the wide one, 1.6 m to the side, is
  // out of reach within the limits; the plain path through the narrow gap is the answer.
  const auto w = wallWithNarrowAndWideGaps();
  mmh::KinematicState start = som_test::atRest(Vector3d(2.0, 0.0, 1.2));
  start.velocity = Vector3d(3.0, 0.0, 0.0);
  mmh::som::SomParams params;
  params.clearance = {10.0, 0.3, 2.5, false};
  const auto out = mmh::som::Planner(params).plan(*w.grid, start, w.target);
  ASSERT_EQ(out.status, mmh::PlanStatus::kOk) << out.detail;
  EXPECT_EQ(out.clearance_fallbacks, 1);
  EXPECT_EQ(gapOfTrajectory(out.trajectory), Gap::kNarrow);
  for (double s = 0.0; s <= out.trajectory.duration(); s += 1e-3)
    ASSERT_FALSE(w.grid->isBlockedPoint(out.trajectory.position(s))) << "blocked at " << s;

  // From rest at the same place the wide gap is taken, with no fallback.
  const auto from_rest =
      mmh::som::Planner(params).plan(*w.grid, som_test::atRest(start.position), w.target);
  ASSERT_EQ(from_rest.status, mmh::PlanStatus::kOk) << from_rest.detail;
  EXPECT_EQ(from_rest.clearance_fallbacks, 0);
  EXPECT_EQ(gapOfTrajectory(from_rest.trajectory), Gap::kWide);
}

namespace {

// SOM's own measure of an answer: jerk energy + time weight x duration.
double costOf(const mmh::som::PlanOutput& out) {
  return out.cost_control + out.cost_time;
}

// The three ways to use the clearance cost on one request: the shortest path only (cost off),
// the path that keeps clear preferred, and both compared.
struct ThreeWays {
  mmh::som::PlanOutput shortest, preferred, compared;
};

ThreeWays planThreeWays(const som_test::World& w, const mmh::KinematicState& start) {
  mmh::som::SomParams off, prefer, compare;
  off.clearance.cost_cells = 0.0;
  prefer.clearance = {10.0, 0.3, 2.5, false};
  compare.clearance = {10.0, 0.3, 2.5, true};
  return {mmh::som::Planner(off).plan(*w.grid, start, w.target),
          mmh::som::Planner(prefer).plan(*w.grid, start, w.target),
          mmh::som::Planner(compare).plan(*w.grid, start, w.target)};
}

}  // namespace

TEST(SomPlanner, ComparedTakesTheNarrowGapOnTheStraightLineWhenItIsTheCheaperWay) {
  // From rest, straight through the narrow gap is faster than round by the wide one (the
  // preference for clearance alone takes the slower way).
  const auto w = wallWithNarrowAndWideGaps();
  const ThreeWays a = planThreeWays(w, som_test::atRest(w.start));
  ASSERT_TRUE(a.shortest.ok() && a.preferred.ok() && a.compared.ok()) << a.compared.detail;
  ASSERT_EQ(gapOfTrajectory(a.shortest.trajectory), Gap::kNarrow);
  ASSERT_EQ(gapOfTrajectory(a.preferred.trajectory), Gap::kWide);
  ASSERT_LT(costOf(a.shortest), costOf(a.preferred));
  EXPECT_EQ(gapOfTrajectory(a.compared.trajectory), Gap::kNarrow);
  EXPECT_EQ(a.compared.clearance_taken, 0);
  EXPECT_DOUBLE_EQ(costOf(a.compared), costOf(a.shortest));
  EXPECT_LT(a.compared.trajectory.duration(), a.preferred.trajectory.duration());
}

TEST(SomPlanner, ComparedKeepsTheCheaperOfTheTwoAnswersInRandomForests) {
  // Pillars of radius 0.15-0.5 m scattered between start and target, 20 forests: the compared
  // answer is the cheaper of the other two whenever both answer, and answers whenever either
  // does. Both outcomes occur, so both branches of the choice are exercised.
  int clear_taken = 0, shortest_kept = 0;
  for (unsigned forest = 0; forest < 20; ++forest) {
    const auto w = som_test::randomPillars(20261207 + forest);
    if (w.grid->isBlockedPoint(w.start) || w.grid->isBlockedPoint(w.target)) continue;
    const ThreeWays a = planThreeWays(w, som_test::atRest(w.start));
    SCOPED_TRACE("forest " + std::to_string(forest));
    EXPECT_EQ(a.compared.ok(), a.shortest.ok() || a.preferred.ok());
    if (!a.compared.ok()) continue;
    double best = std::numeric_limits<double>::infinity();
    if (a.shortest.ok()) best = std::min(best, costOf(a.shortest));
    if (a.preferred.ok()) best = std::min(best, costOf(a.preferred));
    EXPECT_NEAR(costOf(a.compared), best, 1e-9 * best);
    (a.compared.clearance_taken > 0 ? clear_taken : shortest_kept)++;
    for (double s = 0.0; s <= a.compared.trajectory.duration(); s += 2e-3)
      ASSERT_FALSE(w.grid->isOccupiedPoint(a.compared.trajectory.position(s))) << "at " << s;
  }
  EXPECT_GT(clear_taken, 0);
  EXPECT_GT(shortest_kept, 0);
}

TEST(SomPlanner, TheTwoPathsPlannedOnTwoThreadsGiveTheAnswerOfOneThread) {
  // The comparison's second path on its own thread (som.clearance_compare_parallel) is the same
  // work as planned in turn: in 20 forests, from rest and from a fast start turned 60 degrees
  // off the target (where the path from a point ahead is tried too), the same answer to the bit,
  // the same failure, and the same effort counted.
  mmh::som::SomParams in_turn, in_parallel;
  in_turn.clearance.compare_in_parallel = false;
  in_parallel.clearance.compare_in_parallel = true;
  mmh::som::Planner one_thread(in_turn), two_threads(in_parallel);
  int answered = 0, clear_taken = 0, lead_paths = 0;
  for (unsigned forest = 0; forest < 20; ++forest) {
    const auto w = som_test::randomPillars(20261208 + forest);
    if (w.grid->isBlockedPoint(w.start) || w.grid->isBlockedPoint(w.target)) continue;
    mmh::KinematicState fast = som_test::atRest(w.start);
    fast.velocity = 2.5 * (Eigen::AngleAxisd(M_PI / 3.0, Eigen::Vector3d::UnitZ()) *
                           (w.target - w.start).normalized());
    for (const mmh::KinematicState& start : {som_test::atRest(w.start), fast}) {
      SCOPED_TRACE("forest " + std::to_string(forest) + ", start speed " +
                   std::to_string(start.velocity.norm()));
      one_thread.prepare(*w.grid);
      two_threads.prepare(*w.grid);
      const mmh::som::PlanOutput a = one_thread.plan(*w.grid, start, w.target);
      const mmh::som::PlanOutput b = two_threads.plan(*w.grid, start, w.target);
      ASSERT_EQ(a.status, b.status);
      EXPECT_EQ(a.detail, b.detail);
      EXPECT_EQ(a.path, b.path);
      EXPECT_EQ(a.astar_expansions, b.astar_expansions);
      EXPECT_EQ(a.optimizer_evaluations, b.optimizer_evaluations);
      EXPECT_EQ(a.check_margin_retries, b.check_margin_retries);
      EXPECT_EQ(a.lead_paths, b.lead_paths);
      EXPECT_EQ(a.clearance_taken, b.clearance_taken);
      if (!a.ok()) continue;
      ++answered;
      clear_taken += a.clearance_taken;
      lead_paths += a.lead_paths;
      EXPECT_EQ(a.cost_total, b.cost_total);
      ASSERT_EQ(a.trajectory.pieces().size(), b.trajectory.pieces().size());
      for (size_t i = 0; i < a.trajectory.pieces().size(); ++i) {
        EXPECT_EQ(a.trajectory.pieces()[i].duration, b.trajectory.pieces()[i].duration);
        EXPECT_EQ(a.trajectory.pieces()[i].coeffs, b.trajectory.pieces()[i].coeffs);
      }
    }
  }
  // Both ways won somewhere, and fast starts tried the path from a point ahead.
  EXPECT_GT(answered, clear_taken);
  EXPECT_GT(clear_taken, 0);
  EXPECT_GT(lead_paths, 0);
}
