// The MINCO optimisation of SOM: its linear-time coefficients against a dense solve, the full
// objective's analytic gradient against finite differences, the penalty function, and the
// result's boundary conditions and limits.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "mmh/common/grid_astar.hpp"
#include "mmh/common/minco.hpp"
#include "mmh/common/time_map.hpp"
#include "mmh/som/corridor.hpp"
#include "mmh/som/trajectory_optimizer.hpp"
#include "som_test_worlds.hpp"

using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {

struct Fixture {
  som_test::World world;
  mmh::som::Corridor corridor;
  mmh::KinematicState start;
};

Fixture sBendSetup() {
  Fixture s{som_test::sBend(), {}, {}};
  s.start.position = s.world.start;
  s.start.velocity = Vector3d(1.0, 0.5, 0.0);
  s.start.acceleration = Vector3d(0.3, -0.2, 0.1);
  mmh::AStarOptions options;
  options.min_bound = Vector3d(-30, -30, 0.3);
  options.max_bound = Vector3d(30, 30, 2.7);
  mmh::GridAStar astar;
  const auto r = astar.search(*s.world.grid, s.world.start, s.world.target, options);
  EXPECT_TRUE(r.ok());
  mmh::som::CorridorBuilder builder;
  std::string why;
  EXPECT_TRUE(builder.build(*s.world.grid, mmh::shortenPath(*s.world.grid, r.path),
                            Vector3d(-2, -4, 0.3), Vector3d(14, 4, 2.7), {}, {}, &s.corridor,
                            &why));
  return s;
}

}  // namespace

TEST(SmoothedL1, ValueAndSlopeAreContinuous) {
  const double mu = 0.1;
  double g0, g1;
  EXPECT_EQ(mmh::som::smoothedL1(-1.0, mu, &g0), 0.0);
  EXPECT_EQ(g0, 0.0);
  EXPECT_NEAR(mmh::som::smoothedL1(1e-9, mu, &g0), 0.0, 1e-20);
  EXPECT_NEAR(g0, 0.0, 1e-12);
  const double below = mmh::som::smoothedL1(mu - 1e-9, mu, &g0);
  const double above = mmh::som::smoothedL1(mu + 1e-9, mu, &g1);
  EXPECT_NEAR(below, above, 1e-8);
  EXPECT_NEAR(g0, 1.0, 1e-6);
  EXPECT_NEAR(g1, 1.0, 1e-12);
  for (double x : {0.01, 0.05, 0.09, 0.3}) {
    double g, gp, gm;
    mmh::som::smoothedL1(x, mu, &g);
    const double h = 1e-7;
    const double fd =
        (mmh::som::smoothedL1(x + h, mu, &gp) - mmh::som::smoothedL1(x - h, mu, &gm)) / (2 * h);
    EXPECT_NEAR(g, fd, 1e-6) << x;
  }
}

TEST(SomOptimizer, CoefficientsEqualADenseSolve) {
  const Fixture s = sBendSetup();
  mmh::som::TrajectoryOptimizer opt(mmh::som::OptimizerParams(), 3.0, 2.0);
  ASSERT_TRUE(opt.setup(s.start, s.world.target, s.corridor));
  const int m = opt.numPieces();
  ASSERT_GE(m, 3);
  const VectorXd& x = opt.initialGuess();
  const mmh::Trajectory traj = opt.trajectoryAt(x);

  // Same problem through the dense matrix.
  Eigen::Matrix3d head, tail = Eigen::Matrix3d::Zero();
  head << s.start.position, s.start.velocity, s.start.acceleration;
  tail.col(0) = s.world.target;
  Eigen::Matrix3Xd points = Eigen::Map<const Eigen::Matrix3Xd>(x.data(), 3, m - 1);
  VectorXd durations(m);
  for (int i = 0; i < m; ++i) durations[i] = mmh::durationFromTau(x[3 * (m - 1) + i]);
  mmh::MincoJerk minco;
  minco.setConditions(head, tail, m);
  minco.setParameters(points, durations);
  const Eigen::MatrixXd dense = minco.denseMatrix();
  const Eigen::MatrixXd expected = dense.fullPivLu().solve(Eigen::MatrixXd(minco.rightHandSide()));
  for (int i = 0; i < m; ++i) {
    EXPECT_NEAR(traj.pieces()[i].duration, durations[i], 1e-12);
    const Eigen::Matrix<double, 3, 6> got = traj.pieces()[i].coeffs.leftCols(6);
    const Eigen::Matrix<double, 3, 6> want = expected.block(6 * i, 0, 6, 3).transpose();
    EXPECT_LT((got - want).norm(), 1e-7 * (1.0 + want.norm())) << "piece " << i;
  }
}

TEST(SomOptimizer, GradientMatchesFiniteDifferences) {
  const Fixture s = sBendSetup();
  mmh::som::OptimizerParams params;
  params.penalty_smoothing = 0.05;  // wide enough that the differences see a smooth function
  mmh::som::TrajectoryOptimizer opt(params, 3.0, 2.0);
  ASSERT_TRUE(opt.setup(s.start, s.world.target, s.corridor));
  const int m = opt.numPieces();
  // The initial guess, a faster one (velocity and acceleration penalties active) and one with
  // waypoints pushed sideways (corridor penalties active).
  std::vector<VectorXd> points{opt.initialGuess()};
  VectorXd fast = opt.initialGuess();
  fast.tail(m).array() -= 0.8;
  points.push_back(fast);
  VectorXd moved = opt.initialGuess();
  for (int i = 0; i < m - 1; ++i) moved[3 * i + 1] += (i % 2 ? 0.4 : -0.4);
  points.push_back(moved);
  for (size_t k = 0; k < points.size(); ++k) {
    const VectorXd& x = points[k];
    double control, time, penalty;
    opt.costParts(x, &control, &time, &penalty);
    if (k > 0) {
      EXPECT_GT(penalty, 0.0) << k;
    }
    VectorXd g;
    const double f = opt.objective(x, &g);
    EXPECT_NEAR(f, control + time + penalty, 1e-9 * std::abs(f));
    VectorXd fd(x.size());
    for (int i = 0; i < x.size(); ++i) {
      // Penalties in their cubic range curve strongly: a small absolute step.
      const double h = 1e-7;
      VectorXd xp = x, xm = x;
      xp[i] += h;
      xm[i] -= h;
      fd[i] = (opt.objective(xp, nullptr) - opt.objective(xm, nullptr)) / (2 * h);
    }
    Eigen::Index worst;
    (g - fd).cwiseAbs().maxCoeff(&worst);
    EXPECT_LT((g - fd).norm(), 1e-5 * fd.norm())
        << "point " << k << ", worst component " << worst << " of " << x.size() << ": analytic "
        << g[worst] << ", finite differences " << fd[worst];
  }
}

// The ellipsoids only let the corridor penalty skip samples deep inside a polytope: with them or
// without them, the cost and its gradient are the same to the last bit, at points inside and
// points pushed out of the corridor.
TEST(SomOptimizer, TheEllipsoidShortcutChangesNoCostNorGradient) {
  const Fixture s = sBendSetup();
  ASSERT_EQ(s.corridor.ellipsoids.size(), s.corridor.polytopes.size());
  mmh::som::Corridor bare = s.corridor;
  bare.ellipsoids.clear();
  mmh::som::OptimizerParams params;
  mmh::som::TrajectoryOptimizer with(params, 3.0, 2.0), without(params, 3.0, 2.0);
  ASSERT_TRUE(with.setup(s.start, s.world.target, s.corridor));
  ASSERT_TRUE(without.setup(s.start, s.world.target, bare));
  const int m = with.numPieces();
  std::vector<VectorXd> points{with.initialGuess()};
  for (double push : {0.2, 0.6}) {
    VectorXd moved = with.initialGuess();
    for (int i = 0; i < m - 1; ++i) moved[3 * i + 1] += (i % 2 ? push : -push);
    points.push_back(moved);
  }
  bool some_penalty = false;
  for (const VectorXd& x : points) {
    VectorXd g_with, g_without;
    const double f_with = with.objective(x, &g_with);
    const double f_without = without.objective(x, &g_without);
    EXPECT_EQ(f_with, f_without);
    EXPECT_TRUE(g_with == g_without);
    double control, time, penalty;
    with.costParts(x, &control, &time, &penalty);
    some_penalty = some_penalty || penalty > 0.0;
  }
  EXPECT_TRUE(some_penalty) << "no point left the corridor: the faces were never tested";
}

TEST(SomOptimizer, ResultMeetsBoundaryConditionsAndLimits) {
  const Fixture s = sBendSetup();
  mmh::som::OptimizerParams params;
  mmh::som::TrajectoryOptimizer opt(params, 3.0, 2.0);
  ASSERT_TRUE(opt.setup(s.start, s.world.target, s.corridor));
  mmh::som::OptimizerOutput out;
  ASSERT_TRUE(opt.optimize(&out)) << out.message;
  const mmh::Trajectory& t = out.trajectory;
  EXPECT_EQ(t.position(0), s.start.position);
  EXPECT_EQ(t.velocity(0), s.start.velocity);
  EXPECT_EQ(t.acceleration(0), s.start.acceleration);
  EXPECT_LT((t.position(t.duration()) - s.world.target).norm(), 1e-6);
  EXPECT_LT(t.velocity(t.duration()).norm(), 1e-6);
  EXPECT_LT(t.acceleration(t.duration()).norm(), 1e-6);
  // The time stretch works on sampled maxima; the exact ones stay within the verification's 1 %.
  EXPECT_LE(t.maxSpeed(), 3.0 * 1.01);
  EXPECT_LE(t.maxAcceleration(), 2.0 * 1.01);
  EXPECT_GT(out.evaluations, 1);
  EXPECT_NEAR(out.cost_total, out.cost_control + out.cost_time + out.cost_penalty,
              1e-9 * out.cost_total);
  EXPECT_EQ(out.piece_polytope.size(), static_cast<size_t>(t.numPieces()));
}

TEST(SomOptimizer, CornerAwareDurations) {
  using mmh::som::cornerAwareDurations;
  const double vm = 3.0, a = 2.0;
  // A straight line: the rest-to-rest trapezoid (accelerate 1.5 s, cruise, brake 1.5 s).
  const std::vector<Vector3d> line{Vector3d(0, 0, 0), Vector3d(10, 0, 0), Vector3d(20, 0, 0)};
  const auto d_line = cornerAwareDurations(line, 0.0, vm, a);
  ASSERT_EQ(d_line.size(), 2u);
  EXPECT_NEAR(d_line[0] + d_line[1], 20.0 / vm + vm / a, 1e-9);
  EXPECT_NEAR(d_line[0], d_line[1], 1e-9);
  // From 3 m/s to rest over 10 m: cruise 7.75 m, brake 1.5 s.
  const std::vector<Vector3d> one{Vector3d(0, 0, 0), Vector3d(10, 0, 0)};
  EXPECT_NEAR(cornerAwareDurations(one, 3.0, vm, a)[0], 7.75 / 3.0 + 1.5, 1e-9);
  // A right angle between 1 m legs: at most sqrt(a r), r = 0.5 m, at the corner, so both legs
  // take longer than the straight 2 m would, and the corner leg into it no less than at that
  // speed from 3 m/s.
  const std::vector<Vector3d> corner{Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(1, 1, 0)};
  const auto d_corner = cornerAwareDurations(corner, 3.0, vm, a);
  const auto d_straight =
      cornerAwareDurations({Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(2, 0, 0)}, 3.0, vm, a);
  EXPECT_GT(d_corner[0], d_straight[0]);
  EXPECT_GE(d_corner[0], 2.0 * 1.0 / (3.0 + std::sqrt(a * 0.5)) - 1e-9);
}

TEST(SomOptimizer, RefusesAnEmptyCorridor) {
  mmh::som::TrajectoryOptimizer opt(mmh::som::OptimizerParams(), 3.0, 2.0);
  mmh::KinematicState start;
  EXPECT_FALSE(opt.setup(start, Vector3d(1, 0, 0), mmh::som::Corridor()));
  mmh::som::OptimizerOutput out;
  EXPECT_FALSE(opt.optimize(&out));
}
