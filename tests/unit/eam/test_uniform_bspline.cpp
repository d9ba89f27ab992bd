// Uniform cubic B-spline: start control points, exact conversion to polynomial pieces.
#include <gtest/gtest.h>

#include <random>

#include "mmh/eam/uniform_bspline.hpp"

using Eigen::Vector3d;
using mmh::eam::UniformBspline;

namespace {

UniformBspline randomSpline(int n, double dt, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.5);
  Eigen::Matrix3Xd q(3, n);
  for (int i = 0; i < n; ++i)
    q.col(i) = Vector3d(0.4 * i + noise(rng), noise(rng), 1.5 + noise(rng));
  return UniformBspline(q, dt);
}

}  // namespace

TEST(UniformBspline, StartControlPointsReproduceTheStartStateExactly) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int trial = 0; trial < 20; ++trial) {
    mmh::KinematicState s;
    s.position = Vector3d(u(rng), u(rng), u(rng));
    s.velocity = Vector3d(u(rng), u(rng), u(rng));
    s.acceleration = Vector3d(u(rng), u(rng), u(rng));
    const double dt = 0.05 + 0.1 * (trial % 5);
    Eigen::Matrix3Xd q(3, 8);
    q.leftCols(3) = UniformBspline::startControlPoints(s, dt);
    for (int i = 3; i < 8; ++i) q.col(i) = Vector3d(u(rng), u(rng), u(rng));
    const UniformBspline b(q, dt);
    EXPECT_LT((b.evaluate(0, 0.0) - s.position).norm(), 1e-12);
    EXPECT_LT((b.evaluate(1, 0.0) - s.velocity).norm(), 1e-11);
    EXPECT_LT((b.evaluate(2, 0.0) - s.acceleration).norm(), 1e-10);
    // And the converted pieces start there too.
    const mmh::Trajectory t = b.toTrajectory();
    EXPECT_LT((t.position(0.0) - s.position).norm(), 1e-12);
    EXPECT_LT((t.velocity(0.0) - s.velocity).norm(), 1e-11);
    EXPECT_LT((t.acceleration(0.0) - s.acceleration).norm(), 1e-10);
  }
}

TEST(UniformBspline, ConversionToPiecesMatchesDeBoorEverywhere) {
  const UniformBspline b = randomSpline(14, 0.17, 11);
  const mmh::Trajectory traj = b.toTrajectory();
  ASSERT_EQ(traj.numPieces(), b.numSegments());
  EXPECT_NEAR(traj.duration(), b.duration(), 1e-12);
  double worst[4] = {0, 0, 0, 0};
  for (int k = 0; k <= 2000; ++k) {
    const double t = b.duration() * k / 2000.0;
    for (int order = 0; order <= 2; ++order) {
      worst[order] =
          std::max(worst[order], (traj.derivative(order, t) - b.evaluate(order, t)).norm());
    }
    // Jerk is constant per interval and jumps at knots: compare strictly inside intervals.
    const double local = std::fmod(t, b.knotSpan());
    if (local > 1e-6 && local < b.knotSpan() - 1e-6)
      worst[3] = std::max(worst[3], (traj.derivative(3, t) - b.evaluate(3, t)).norm());
  }
  EXPECT_LT(worst[0], 1e-11);
  EXPECT_LT(worst[1], 1e-10);
  EXPECT_LT(worst[2], 1e-9);
  EXPECT_LT(worst[3], 1e-8);
}

TEST(UniformBspline, PiecesJoinWithContinuousPositionVelocityAcceleration) {
  const UniformBspline b = randomSpline(12, 0.21, 5);
  const mmh::Trajectory traj = b.toTrajectory();
  for (int i = 0; i + 1 < traj.numPieces(); ++i) {
    const mmh::Piece& a = traj.pieces()[i];
    const mmh::Piece& c = traj.pieces()[i + 1];
    for (int order = 0; order <= 2; ++order) {
      EXPECT_LT((a.derivative(order, a.duration) - c.derivative(order, 0.0)).norm(), 1e-9)
          << "piece " << i << " order " << order;
    }
  }
}

TEST(UniformBspline, ThreeEqualLastControlPointsEndAtRest) {
  UniformBspline b = randomSpline(10, 0.2, 8);
  const Vector3d target(4.0, 1.0, 1.2);
  for (int i = 7; i < 10; ++i) b.controlPoints().col(i) = target;
  const mmh::Trajectory traj = b.toTrajectory();
  const double T = traj.duration();
  EXPECT_LT((traj.position(T) - target).norm(), 1e-12);
  EXPECT_LT(traj.velocity(T).norm(), 1e-10);
  EXPECT_LT(traj.acceleration(T).norm(), 1e-9);
}
