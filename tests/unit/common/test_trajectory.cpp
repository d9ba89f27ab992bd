#include <gtest/gtest.h>

#include <cmath>

#include "mmh/common/msg_convert.hpp"
#include "mmh/common/trajectory.hpp"

using mmh::Piece;
using mmh::Trajectory;

namespace {

// x(t) = c0 + c1 t + ... on axis `axis`, others zero.
Piece axisPiece(double duration, int axis, std::initializer_list<double> coeffs) {
  Piece p;
  p.duration = duration;
  int k = 0;
  for (double c : coeffs) p.coeffs(axis, k++) = c;
  return p;
}

}  // namespace

TEST(Trajectory, EvaluatesDerivativesOfCubic) {
  Trajectory t({axisPiece(2.0, 0, {1.0, 2.0, 3.0, 4.0})});  // 1 + 2t + 3t^2 + 4t^3
  EXPECT_NEAR(t.position(1.5).x(), 1 + 3 + 6.75 + 13.5, 1e-12);
  EXPECT_NEAR(t.velocity(1.5).x(), 2 + 9 + 27, 1e-12);
  EXPECT_NEAR(t.acceleration(1.5).x(), 6 + 36, 1e-12);
  EXPECT_NEAR(t.jerk(1.5).x(), 24, 1e-12);
  EXPECT_DOUBLE_EQ(t.duration(), 2.0);
  // Clamped outside [0, T].
  EXPECT_NEAR(t.position(5.0).x(), t.position(2.0).x(), 1e-12);
}

TEST(Trajectory, PiecesAreChainedInTime) {
  Trajectory t({axisPiece(1.0, 1, {0.0, 1.0}), axisPiece(2.0, 1, {1.0, 2.0})});
  EXPECT_NEAR(t.position(0.5).y(), 0.5, 1e-12);
  EXPECT_NEAR(t.position(2.0).y(), 1.0 + 2.0 * 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(t.duration(), 3.0);
}

TEST(Trajectory, ArcLengthOfLineAndParabola) {
  Trajectory line({axisPiece(3.0, 0, {0.0, 2.0})});
  EXPECT_NEAR(line.arcLength(), 6.0, 1e-12);
  EXPECT_NEAR(line.arcLength(1.0, 2.0), 2.0, 1e-12);
  // y = t^2 on [0, 1] with x = t: length = int sqrt(1 + 4t^2) dt
  Piece p;
  p.duration = 1.0;
  p.coeffs(0, 1) = 1.0;
  p.coeffs(1, 2) = 1.0;
  const double exact = 0.5 * std::sqrt(5.0) + 0.25 * std::asinh(2.0);
  EXPECT_NEAR(Trajectory({p}).arcLength(), exact, 1e-9);
}

TEST(Trajectory, JerkEnergyIsExact) {
  // x = t^3 -> jerk 6, energy 36 T; y = t^4 -> jerk 24 t, energy 576 T^3 / 3.
  Piece p;
  p.duration = 2.0;
  p.coeffs(0, 3) = 1.0;
  p.coeffs(1, 4) = 1.0;
  EXPECT_NEAR(Trajectory({p}).jerkEnergy(), 36 * 2 + 576 * 8 / 3.0, 1e-9);
}

TEST(Trajectory, MaxSpeedAndAccelerationAreExact) {
  // Circle of radius 2 approximated... use x = sin-free polynomial: v = (1 - t^2, 2t), |v|^2 =
  // (1 + t^2)^2 -> |v| = 1 + t^2, max at t = T.
  Piece p;
  p.duration = 1.5;
  p.coeffs(0, 1) = 1.0;
  p.coeffs(0, 3) = -1.0 / 3.0;
  p.coeffs(1, 2) = 1.0;
  Trajectory t({p});
  double at = 0;
  EXPECT_NEAR(t.maxSpeed(&at), 1 + 1.5 * 1.5, 1e-9);
  EXPECT_NEAR(at, 1.5, 1e-9);
  // a = (-2t, 2), |a| max at t = 1.5: sqrt(9 + 4)
  EXPECT_NEAR(t.maxAcceleration(), std::sqrt(13.0), 1e-9);
  // Interior maximum: x = 3t^2 - t^3 on [0, 2]: v = 6t - 3t^2, max 3 at t = 1.
  Trajectory u({axisPiece(2.0, 0, {0.0, 0.0, 3.0, -1.0})});
  EXPECT_NEAR(u.maxSpeed(&at), 3.0, 1e-9);
  EXPECT_NEAR(at, 1.0, 1e-6);
}

TEST(Trajectory, TailKeepsTheCurve) {
  Trajectory t({axisPiece(1.0, 0, {0.0, 1.0, 0.5, -0.2}), axisPiece(2.0, 0, {1.3, 1.4, -0.1})});
  Trajectory tail = t.tail(0.4);
  EXPECT_NEAR(tail.duration(), 2.6, 1e-12);
  for (double s : {0.0, 0.3, 0.6, 1.1, 2.6}) {
    EXPECT_NEAR(tail.position(s).x(), t.position(0.4 + s).x(), 1e-12);
    EXPECT_NEAR(tail.velocity(s).x(), t.velocity(0.4 + s).x(), 1e-12);
    EXPECT_NEAR(tail.acceleration(s).x(), t.acceleration(0.4 + s).x(), 1e-12);
  }
}

TEST(Trajectory, HeadKeepsTheCurveUpToItsEnd) {
  Trajectory t({axisPiece(1.0, 0, {0.0, 1.0, 0.5, -0.2}), axisPiece(2.0, 0, {1.3, 1.4, -0.1})});
  for (double t1 : {0.4, 1.0, 1.7, 3.0, 5.0}) {
    Trajectory head = t.head(t1);
    EXPECT_NEAR(head.duration(), std::min(t1, 3.0), 1e-12);
    for (double s = 0.0; s <= head.duration(); s += 0.1) {
      EXPECT_NEAR(head.position(s).x(), t.position(s).x(), 1e-12);
      EXPECT_NEAR(head.acceleration(s).x(), t.acceleration(s).x(), 1e-12);
    }
  }
  EXPECT_EQ(t.head(1.0).numPieces(), 1);
  EXPECT_NEAR(t.head(0.0).duration(), 0.0, 1e-12);
}

TEST(Trajectory, MessageRoundTrip) {
  Trajectory t({axisPiece(1.0, 0, {0.0, 1.0, 0.5, -0.2, 0.1, 0.01, 0.001, 1e-4}),
                axisPiece(0.5, 2, {1.0, -1.0})});
  mmh::trajectory_t msg{};
  mmh::toMsg(t, msg);
  EXPECT_EQ(msg.num_pieces, 2);
  Trajectory back = mmh::fromMsg(msg);
  ASSERT_EQ(back.numPieces(), 2);
  EXPECT_TRUE(back.pieces()[0].coeffs.isApprox(t.pieces()[0].coeffs));
  EXPECT_DOUBLE_EQ(back.pieces()[1].duration, 0.5);
  EXPECT_TRUE(back.isFinite());
  back.pieces()[0].coeffs(1, 1) = std::nan("");
  EXPECT_FALSE(back.isFinite());
}
