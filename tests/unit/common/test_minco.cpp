#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "mmh/common/minco.hpp"
#include "mmh/common/minco_penalty.hpp"
#include "mmh/common/time_map.hpp"

using Eigen::Matrix3d;
using Eigen::Matrix3Xd;
using Eigen::MatrixX3d;
using Eigen::VectorXd;

namespace {

struct Problem {
  Matrix3d head, tail;
  Matrix3Xd points;
  VectorXd durations;
};

Problem randomProblem(int pieces, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), d(0.4, 2.0);
  Problem p;
  p.head = Matrix3d::NullaryExpr([&](Eigen::Index, Eigen::Index) { return u(rng); });
  p.tail = Matrix3d::NullaryExpr([&](Eigen::Index, Eigen::Index) { return u(rng); });
  p.tail.col(0) += Eigen::Vector3d(5, 2, 1);
  p.points =
      Matrix3Xd::NullaryExpr(3, pieces - 1, [&](Eigen::Index, Eigen::Index) { return 3 * u(rng); });
  p.durations = VectorXd::NullaryExpr(pieces, [&](Eigen::Index) { return d(rng); });
  return p;
}

// A cost that depends on everything: energy + a smooth speed penalty.
double cost(mmh::MincoJerk& m, const Problem& p, MatrixX3d* gc, VectorXd* gt) {
  m.setParameters(p.points, p.durations);
  MatrixX3d grad_c = MatrixX3d::Zero(6 * m.numPieces(), 3);
  VectorXd grad_t = VectorXd::Zero(m.numPieces());
  double c = m.energy();
  m.addEnergyGradient(grad_c, grad_t);
  c += mmh::integratePenalty(
      m, 8,
      [](const mmh::PenaltyPoint& pt, Eigen::Vector3d& gp, Eigen::Vector3d& gv, Eigen::Vector3d&) {
        const double s = pt.vel.squaredNorm() - 1.0;
        gv = 2.0 * s * 2.0 * pt.vel;
        gp = 0.1 * pt.pos;
        return s * s + 0.05 * pt.pos.squaredNorm();
      },
      grad_c, grad_t);
  if (gc) *gc = grad_c;
  if (gt) *gt = grad_t;
  return c;
}

}  // namespace

TEST(Minco, BandedSolveEqualsDenseSolve) {
  for (int pieces : {1, 2, 5, 12}) {
    Problem p = randomProblem(pieces, 10 + pieces);
    mmh::MincoJerk m;
    m.setConditions(p.head, p.tail, pieces);
    m.setParameters(p.points, p.durations);
    Eigen::MatrixXd dense = m.denseMatrix();
    MatrixX3d expected = dense.fullPivLu().solve(Eigen::MatrixXd(m.rightHandSide()));
    EXPECT_LT((m.coeffs() - expected).norm(), 1e-8 * (1.0 + expected.norm())) << pieces;
  }
}

TEST(Minco, MeetsBoundaryConditionsAndContinuity) {
  Problem p = randomProblem(6, 3);
  mmh::MincoJerk m;
  m.setConditions(p.head, p.tail, 6);
  m.setParameters(p.points, p.durations);
  mmh::Trajectory t = m.trajectory();
  EXPECT_TRUE(t.position(0).isApprox(p.head.col(0), 1e-9));
  EXPECT_TRUE(t.velocity(0).isApprox(p.head.col(1), 1e-9));
  EXPECT_TRUE(t.acceleration(0).isApprox(p.head.col(2), 1e-9));
  EXPECT_LT((t.position(t.duration()) - p.tail.col(0)).norm(), 1e-8);
  EXPECT_LT((t.velocity(t.duration()) - p.tail.col(1)).norm(), 1e-8);
  EXPECT_LT((t.acceleration(t.duration()) - p.tail.col(2)).norm(), 1e-8);
  double time = 0.0;
  for (int i = 0; i < 5; ++i) {
    time += p.durations[i];
    const mmh::Piece& a = t.pieces()[i];
    const mmh::Piece& b = t.pieces()[i + 1];
    EXPECT_LT((a.position(a.duration) - p.points.col(i)).norm(), 1e-8);
    for (int order = 0; order <= 4; ++order) {
      EXPECT_LT((a.derivative(order, a.duration) - b.derivative(order, 0.0)).norm(), 1e-7)
          << "order " << order << " at junction " << i;
    }
  }
}

TEST(Minco, EnergyMatchesExactIntegral) {
  Problem p = randomProblem(4, 5);
  mmh::MincoJerk m;
  m.setConditions(p.head, p.tail, 4);
  m.setParameters(p.points, p.durations);
  EXPECT_NEAR(m.energy(), m.trajectory().jerkEnergy(), 1e-8 * m.energy());
}

TEST(Minco, GradientMatchesFiniteDifferences) {
  Problem p = randomProblem(5, 7);
  mmh::MincoJerk m;
  m.setConditions(p.head, p.tail, 5);
  MatrixX3d gc;
  VectorXd gt;
  cost(m, p, &gc, &gt);
  Matrix3Xd grad_q;
  VectorXd grad_T;
  m.setParameters(p.points, p.durations);
  m.propagateGradient(gc, gt, grad_q, grad_T);
  const double h = 1e-6;
  for (int i = 0; i < p.points.cols(); ++i) {
    for (int a = 0; a < 3; ++a) {
      Problem plus = p, minus = p;
      plus.points(a, i) += h;
      minus.points(a, i) -= h;
      const double fd =
          (cost(m, plus, nullptr, nullptr) - cost(m, minus, nullptr, nullptr)) / (2 * h);
      EXPECT_NEAR(grad_q(a, i), fd, 1e-4 * (1.0 + std::abs(fd))) << "q(" << a << "," << i << ")";
    }
  }
  for (int i = 0; i < p.durations.size(); ++i) {
    Problem plus = p, minus = p;
    plus.durations[i] += h;
    minus.durations[i] -= h;
    const double fd =
        (cost(m, plus, nullptr, nullptr) - cost(m, minus, nullptr, nullptr)) / (2 * h);
    EXPECT_NEAR(grad_T[i], fd, 1e-4 * (1.0 + std::abs(fd))) << "T" << i;
  }
}

TEST(TimeMap, IsABijectionWithCorrectGradient) {
  for (double tau : {-3.0, -0.5, 0.0, 0.2, 2.5}) {
    const double t = mmh::durationFromTau(tau);
    EXPECT_GT(t, 0.0);
    EXPECT_NEAR(mmh::tauFromDuration(t), tau, 1e-9);
    const double fd = (mmh::durationFromTau(tau + 1e-6) - mmh::durationFromTau(tau - 1e-6)) / 2e-6;
    EXPECT_NEAR(mmh::durationGradient(tau), fd, 1e-6);
  }
}
