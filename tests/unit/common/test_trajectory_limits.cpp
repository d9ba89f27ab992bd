// The shared exact-maxima routine: known answers for every method.
#include <gtest/gtest.h>

#include <algorithm>

#include "mmh/common/trajectory_limits.hpp"

namespace {

using mmh::MaximaMethod;

// x(t) = t^2 - t^3 / 3 on [0, 2]: v = 2t - t^2 peaks at 1 (t = 1, interior), a = 2 - 2t peaks
// at |2| at both ends.
mmh::Trajectory interiorPeak() {
  mmh::Piece p;
  p.duration = 2.0;
  p.coeffs(0, 2) = 1.0;
  p.coeffs(0, 3) = -1.0 / 3.0;
  return mmh::Trajectory({p});
}

TEST(TrajectoryLimits, EveryMethodFindsTheInteriorSpeedPeak) {
  for (MaximaMethod m : {MaximaMethod::kStationaryPoints, MaximaMethod::kBernsteinBound,
                         MaximaMethod::kCubicClosedForm}) {
    const mmh::KinematicMaxima r = mmh::trajectoryMaxima(interiorPeak(), m);
    EXPECT_NEAR(r.max_speed, 1.0, 1e-8) << static_cast<int>(m);
    EXPECT_NEAR(r.max_acc, 2.0, 1e-8) << static_cast<int>(m);
  }
  double at = 0.0;
  EXPECT_NEAR(mmh::maxDerivativeNorm(interiorPeak(), 1, &at), 1.0, 1e-12);
  EXPECT_NEAR(at, 1.0, 1e-6);
}

TEST(TrajectoryLimits, BernsteinBoundIsNeverBelowTheMaximum) {
  const mmh::Piece p = interiorPeak().pieces()[0];
  EXPECT_GE(mmh::bernsteinMaxDerivativeNorm(p, 1), 1.0);
  EXPECT_LE(mmh::bernsteinMaxDerivativeNorm(p, 1), 1.0 + 1e-8);
}

TEST(TrajectoryLimits, ClosedFormFallsBackOnHigherDegreePieces) {
  mmh::Trajectory t = interiorPeak();
  t.pieces()[0].coeffs(1, 5) = 0.01;  // degree 5 on y
  EXPECT_FALSE(mmh::allPiecesCubic(t));
  const mmh::KinematicMaxima closed = mmh::trajectoryMaxima(t, MaximaMethod::kCubicClosedForm);
  const mmh::KinematicMaxima roots = mmh::trajectoryMaxima(t, MaximaMethod::kStationaryPoints);
  EXPECT_EQ(closed.max_speed, roots.max_speed);  // the same routine, bit for bit
  EXPECT_EQ(closed.max_acc, roots.max_acc);
}

TEST(TrajectoryLimits, QuadraticNormAndCubicRoots) {
  // |(1 - t) , t, 0|^2 on [0, 1]: ends 1, minimum 0.5 at t = 0.5; with best = 3 stays 3.
  const Eigen::Vector3d b0(1, 0, 0), b1(-1, 1, 0), b2 = Eigen::Vector3d::Zero();
  EXPECT_DOUBLE_EQ(mmh::maxSquaredQuadraticNorm(b0, b1, b2, 1.0, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(mmh::maxSquaredQuadraticNorm(b0, b1, b2, 1.0, 3.0), 3.0);
  double roots[3];
  ASSERT_EQ(mmh::cubicRoots(1.0, -6.0, 11.0, -6.0, roots), 3);  // (x-1)(x-2)(x-3)
  std::sort(roots, roots + 3);
  EXPECT_NEAR(roots[0], 1.0, 1e-12);
  EXPECT_NEAR(roots[1], 2.0, 1e-12);
  EXPECT_NEAR(roots[2], 3.0, 1e-12);
  ASSERT_EQ(mmh::cubicRoots(0.0, 0.0, 2.0, -4.0, roots), 1);  // linear
  EXPECT_DOUBLE_EQ(roots[0], 2.0);
}

TEST(TrajectoryLimits, WithinUsesAnAbsoluteTolerance) {
  mmh::KinematicMaxima m;
  m.max_speed = 3.0 + 5e-10;
  m.max_acc = 2.0;
  EXPECT_TRUE(m.within(3.0, 2.0));
  EXPECT_FALSE(m.within(3.0, 2.0, 1e-10));
}

}  // namespace
