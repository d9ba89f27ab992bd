// The EAM objective: analytic gradients against finite differences, the collision penalty's
// shape, and the optimiser keeping the fixed control points.
#include <gtest/gtest.h>

#include <random>

#include "mmh/eam/bspline_cost.hpp"
#include "mmh/eam/bspline_optimizer.hpp"

using Eigen::Vector3d;
using namespace mmh::eam;

namespace {

// Control points with speeds and accelerations beyond the limits, pairs in every branch of the
// penalty (satisfied, cubic, quadratic), points outside the box.
struct Problem {
  Eigen::Matrix3Xd q;
  PairSet pairs;
  CostSettings settings;
};

Problem makeProblem() {
  Problem pb;
  std::mt19937_64 rng(17);
  std::normal_distribution<double> n(0.0, 1.0);
  pb.q.resize(3, 14);
  for (int i = 0; i < 14; ++i)
    pb.q.col(i) = Vector3d(0.5 * i + 0.2 * n(rng), 0.3 * n(rng), 1.5 + 0.1 * n(rng));
  pb.pairs.resize(14);
  const double depth[] = {-0.3, 0.05, 0.15, 0.6, -0.05, 0.3, 0.02, 0.9};
  for (int i = 3; i < 11; ++i) {
    const Vector3d v = Vector3d(0.2, 1.0, 0.1 * n(rng)).normalized();
    // d = (q - p).v = clearance - depth  =>  p = q - (clearance - depth) v
    pb.pairs[i].push_back({pb.q.col(i) - (0.1 - depth[i - 3]) * v, v, 0.1});
  }
  pb.pairs[6].push_back({pb.q.col(6) + Vector3d(0.0, 0.2, 0.0), Vector3d(0, -1, 0), 0.05});
  pb.settings.max_vel_mps = 1.0;  // the points are ~0.5 m apart at dt = 0.2: 2.5 m/s
  pb.settings.max_acc_mps2 = 1.0;
  pb.settings.box_min = Vector3d(-10, -10, 1.45);
  pb.settings.box_max = Vector3d(10, 10, 1.58);
  return pb;
}

}  // namespace

TEST(BsplineCost, GradientMatchesFiniteDifferences) {
  Problem pb = makeProblem();
  const CostWeights w{1.3, 250.0, 7.0};
  const BsplineCost cost(pb.settings, w, &pb.pairs);
  const double dt = 0.2;
  Eigen::Matrix3Xd g;
  const CostTerms t = cost.evaluate(pb.q, dt, &g);
  ASSERT_GT(t.smooth, 0.0);
  ASSERT_GT(t.collision, 0.0);
  ASSERT_GT(t.feasibility, 0.0);
  for (int i = 0; i < pb.q.cols(); ++i) {
    for (int a = 0; a < 3; ++a) {
      const double h = 1e-6;
      Eigen::Matrix3Xd qp = pb.q, qm = pb.q;
      qp(a, i) += h;
      qm(a, i) -= h;
      const double fd =
          (cost.evaluate(qp, dt, nullptr).total - cost.evaluate(qm, dt, nullptr).total) / (2 * h);
      EXPECT_NEAR(g(a, i), fd, 1e-5 * std::max(1.0, std::abs(fd)))
          << "point " << i << " axis " << a;
    }
  }
}

TEST(BsplineCost, PartialEvaluationHasTheSameGradientForItsPoints) {
  Problem pb = makeProblem();
  const BsplineCost cost(pb.settings, CostWeights{1.0, 100.0, 3.0}, &pb.pairs);
  Eigen::Matrix3Xd full, part;
  cost.evaluate(pb.q, 0.2, &full);
  cost.evaluate(pb.q, 0.2, &part, 5, 8);
  for (int i = 5; i <= 8; ++i) EXPECT_LT((full.col(i) - part.col(i)).norm(), 1e-9);
}

TEST(BsplineCost, CollisionPenaltyIsZeroWhenClearAndSmoothAtTheClearance) {
  double d = 0.0;
  EXPECT_EQ(collisionPenalty(-0.1, 0.1, &d), 0.0);
  EXPECT_EQ(d, 0.0);
  EXPECT_EQ(collisionPenalty(0.0, 0.1, &d), 0.0);
  double d1 = 0.0, d2 = 0.0;
  const double below = collisionPenalty(0.1 - 1e-9, 0.1, &d1);
  const double above = collisionPenalty(0.1 + 1e-9, 0.1, &d2);
  EXPECT_NEAR(below, above, 1e-9);
  EXPECT_NEAR(d1, d2, 1e-7);
  // Deeper is always worse.
  double prev = 0.0;
  for (double c = 0.01; c < 2.0; c += 0.01) {
    const double f = collisionPenalty(c, 0.1, &d);
    EXPECT_GT(f, prev);
    EXPECT_GT(d, 0.0);
    prev = f;
  }
}

TEST(BsplineOptimizer, LowersTheCostAndKeepsTheFixedPoints) {
  Problem pb = makeProblem();
  pb.settings.max_vel_mps = 3.0;
  pb.settings.max_acc_mps2 = 3.0;
  pb.settings.box_min = Vector3d::Constant(-100);
  pb.settings.box_max = Vector3d::Constant(100);
  const BsplineCost cost(pb.settings, CostWeights{1.0, 1000.0, 1.0}, &pb.pairs);
  UniformBspline spline(pb.q, 0.2);
  const double before = cost.evaluate(pb.q, 0.2, nullptr).total;
  const OptimizeResult r = optimizeControlPoints(spline, cost, 300);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_LT(r.terms.total, 0.5 * before);
  const Eigen::Matrix3Xd& q = spline.controlPoints();
  for (int i : {0, 1, 2, 11, 12, 13}) EXPECT_EQ((q.col(i) - pb.q.col(i)).norm(), 0.0);
}

TEST(BsplineCost, GeofenceWallsStandTheMarginInsideTheFence) {
  EamParams p;
  p.geofence_min = Vector3d(-30, -30, 0.3);
  p.geofence_max = Vector3d(30, 30, 2.7);
  p.geofence_margin_m = 0.05;
  const CostSettings s = costSettingsFor(p);
  EXPECT_TRUE(s.box_min.isApprox(Vector3d(-29.95, -29.95, 0.35)));
  EXPECT_TRUE(s.box_max.isApprox(Vector3d(29.95, 29.95, 2.65)));
  EXPECT_EQ(s.max_vel_mps, p.max_vel_mps);
  EXPECT_EQ(s.max_acc_mps2, p.max_acc_mps2);
  // A control point pressed against the fence costs something now: the soft wall no longer lets
  // the curve end a few millimetres outside the fence, which the verification refuses.
  Eigen::Matrix3Xd q(3, 4);
  for (int i = 0; i < 4; ++i) q.col(i) = Vector3d(0.3 * i, 0.0, 2.69);
  const PairSet no_pairs(4);
  const BsplineCost cost(s, CostWeights{0.0, 1.0, 0.0}, &no_pairs);
  EXPECT_GT(cost.evaluate(q, 0.2, nullptr).collision, 0.0);
  p.geofence_margin_m = 0.0;
  EXPECT_EQ(BsplineCost(costSettingsFor(p), CostWeights{0.0, 1.0, 0.0}, &no_pairs)
                .evaluate(q, 0.2, nullptr)
                .collision,
            0.0);
  // A fence thinner than twice the margin keeps its middle, never inverted walls.
  p.geofence_margin_m = 0.5;
  p.geofence_min.z() = 1.0;
  p.geofence_max.z() = 1.4;
  const CostSettings thin = costSettingsFor(p);
  EXPECT_DOUBLE_EQ(thin.box_min.z(), 1.2);
  EXPECT_DOUBLE_EQ(thin.box_max.z(), 1.2);
}
