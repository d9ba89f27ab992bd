// The FPM cost and its analytic gradient (checked against central finite differences), and what
// the optimiser does with it.
#include <gtest/gtest.h>

#include <random>

#include "mmh/fpm/spatio_temporal_optimizer.hpp"

using Eigen::Vector3d;
using mmh::fpm::KnotState;

namespace {

struct KnotProblem {
  std::vector<KnotState> knots;
  std::vector<bool> fixed;
  Eigen::VectorXd durations;
};

// A wiggly 6-piece trajectory that breaks both limits somewhere, one waypoint fixed.
KnotProblem wiggly(uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), d(0.3, 1.5);
  KnotProblem s;
  for (int i = 0; i <= 6; ++i) {
    KnotState k;
    k.p = Vector3d(2.0 * i, 0.0, 1.0) + Vector3d(u(rng), u(rng), u(rng));
    k.v = Vector3d(2.5, 0.0, 0.0) + 2.0 * Vector3d(u(rng), u(rng), u(rng));
    k.a = 2.0 * Vector3d(u(rng), u(rng), u(rng));
    s.knots.push_back(k);
  }
  s.knots.back().v.setZero();
  s.knots.back().a.setZero();
  s.fixed = {false, false, true, false, false};
  s.durations.resize(6);
  for (int i = 0; i < 6; ++i) s.durations[i] = d(rng);
  return s;
}

mmh::fpm::OptimizerSettings settings() {
  mmh::fpm::OptimizerSettings st;
  st.v_limit = 3.0;
  st.a_limit = 2.0;
  st.penalty_weight = 50.0;  // moderate, so that the penalty terms do not swamp the check
  st.samples_per_piece = 7;
  return st;
}

void checkGradient(mmh::fpm::SpatioTemporalOptimizer& opt) {
  opt.setSettings(settings());
  std::vector<double> x = opt.pack(), grad;
  const double f0 = opt.evaluate(x, &grad);
  ASSERT_TRUE(std::isfinite(f0));
  for (size_t i = 0; i < x.size(); ++i) {
    // The cost is large (strong penalties): a step this size keeps rounding below truncation.
    const double h = 1e-5 * std::max(1.0, std::abs(x[i]));
    std::vector<double> xp = x, xm = x;
    xp[i] += h;
    xm[i] -= h;
    const double fd = (opt.evaluate(xp, nullptr) - opt.evaluate(xm, nullptr)) / (2.0 * h);
    EXPECT_NEAR(grad[i], fd, 1e-5 * std::max(1.0, std::abs(fd))) << "variable " << i;
  }
}

}  // namespace

TEST(FpmOptimizer, GradientMatchesFiniteDifferencesInSpace) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    const KnotProblem s = wiggly(seed);
    mmh::fpm::SpatioTemporalOptimizer opt;
    opt.setup(s.knots, s.fixed, s.durations);
    checkGradient(opt);
  }
}

TEST(FpmOptimizer, GradientMatchesFiniteDifferencesOnALineAndInAPlane) {
  const KnotProblem s = wiggly(4);
  mmh::fpm::SpatioTemporalOptimizer line;
  line.setup(s.knots, std::vector<bool>(5, false), s.durations);
  line.restrictTo(Vector3d(0, 0, 1), Vector3d::UnitX());
  checkGradient(line);
  mmh::fpm::SpatioTemporalOptimizer plane;
  plane.setup(s.knots, std::vector<bool>(5, false), s.durations);
  Eigen::Matrix3Xd basis(3, 2);
  basis << 1, 0, 0, 0.6, 0, 0.8;
  plane.restrictTo(Vector3d(0, 0, 1), basis);
  checkGradient(plane);
}

TEST(FpmOptimizer, OptimisingLowersTheCostAndKeepsEndsAndWaypoints) {
  const KnotProblem s = wiggly(5);
  mmh::fpm::SpatioTemporalOptimizer opt;
  opt.setup(s.knots, s.fixed, s.durations);
  auto st = settings();
  st.max_evaluations = 200;
  const double before = opt.costs(st).total();
  const int evals = opt.optimize(st);
  EXPECT_GT(evals, 1);
  EXPECT_LT(opt.costs(st).total(), before);
  const mmh::Trajectory t = opt.trajectory();
  EXPECT_LT((t.position(0.0) - s.knots.front().p).norm(), 1e-12);
  EXPECT_LT((t.velocity(0.0) - s.knots.front().v).norm(), 1e-12);
  EXPECT_LT((t.acceleration(0.0) - s.knots.front().a).norm(), 1e-12);
  EXPECT_LT((t.position(t.duration()) - s.knots.back().p).norm(), 1e-8);
  EXPECT_LT(t.velocity(t.duration()).norm(), 1e-8);
  EXPECT_EQ(opt.knots()[3].p, s.knots[3].p);  // the fixed waypoint did not move
}
