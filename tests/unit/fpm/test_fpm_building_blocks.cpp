// FPM building blocks: quintic pieces from knot states, the Bernstein limit proof, speed profiles.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mmh/common/trajectory_limits.hpp"
#include "mmh/fpm/hermite_pieces.hpp"
#include "mmh/fpm/speed_profile.hpp"

using Eigen::Vector3d;
using mmh::fpm::KnotState;

namespace {

Vector3d randomVector(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return Vector3d(u(rng), u(rng), u(rng));
}

KnotState randomKnot(std::mt19937& rng) {
  return KnotState{randomVector(rng, 5.0), randomVector(rng, 3.0), randomVector(rng, 2.0)};
}

// Largest |derivative| over dense samples of the piece.
double sampledMax(const mmh::Piece& p, int order) {
  double m = 0.0;
  for (int i = 0; i <= 20000; ++i)
    m = std::max(m, p.derivative(order, p.duration * i / 20000).norm());
  return m;
}

}  // namespace

TEST(HermitePieces, QuinticMatchesBothKnotStates) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> dur(0.01, 5.0);
  for (int k = 0; k < 200; ++k) {
    const KnotState a = randomKnot(rng), b = randomKnot(rng);
    const double T = dur(rng);
    mmh::Piece p;
    p.duration = T;
    p.coeffs.leftCols(6) = mmh::fpm::hermiteQuintic(a, b, T);
    const double scale = 1.0 + 10.0 / (T * T);
    EXPECT_LT((p.position(0) - a.p).norm(), 1e-12);
    EXPECT_LT((p.velocity(0) - a.v).norm(), 1e-12);
    EXPECT_LT((p.acceleration(0) - a.a).norm(), 1e-12);
    EXPECT_LT((p.position(T) - b.p).norm(), 1e-9 * scale);
    EXPECT_LT((p.velocity(T) - b.v).norm(), 1e-9 * scale);
    EXPECT_LT((p.acceleration(T) - b.a).norm(), 1e-9 * scale);
  }
}

TEST(HermitePieces, CubicIsReproducedExactly) {
  // A constant-jerk piece (as in S-curves) is a quintic with c4 = c5 = 0.
  const Vector3d p0(1, 2, 3), v0(0.5, -1, 0), a0(0.2, 0.1, -0.3), j(3, -2, 1);
  const double T = 0.7;
  KnotState a{p0, v0, a0}, b;
  b.p = p0 + v0 * T + a0 * T * T / 2 + j * T * T * T / 6;
  b.v = v0 + a0 * T + j * T * T / 2;
  b.a = a0 + j * T;
  const auto c = mmh::fpm::hermiteQuintic(a, b, T);
  EXPECT_LT(c.col(3).cwiseAbs().maxCoeff() - j.cwiseAbs().maxCoeff() / 6.0, 1e-12);
  EXPECT_LT(c.col(4).norm(), 1e-10);
  EXPECT_LT(c.col(5).norm(), 1e-10);
  EXPECT_NEAR(mmh::fpm::quinticJerkEnergy(c, T), j.squaredNorm() * T, 1e-9);
}

TEST(LimitCheck, BernsteinMaximaAgreeWithPolynomialRootsAndNeverUnderestimate) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0), dur(0.05, 4.0);
  for (int k = 0; k < 300; ++k) {
    mmh::Piece p;
    p.duration = dur(rng);
    for (int a = 0; a < 3; ++a)
      for (int j = 0; j < 6; ++j) p.coeffs(a, j) = u(rng) * std::pow(1.5, -j);
    const mmh::Trajectory one({p});
    const double v = mmh::bernsteinMaxDerivativeNorm(p, 1),
                 a = mmh::bernsteinMaxDerivativeNorm(p, 2);
    // Same maxima as the root-based ones of common/ (an independent method) ...
    EXPECT_NEAR(v, one.maxSpeed(), 1e-8 * std::max(1.0, v));
    EXPECT_NEAR(a, one.maxAcceleration(), 1e-8 * std::max(1.0, a));
    // ... and never below any sample: it is an upper bound.
    EXPECT_GE(v, sampledMax(p, 1) - 1e-12);
    EXPECT_GE(a, sampledMax(p, 2) - 1e-12);
  }
}

TEST(LimitCheck, FlatMaximumAndDegreeSevenPieces) {
  mmh::Piece cruise;  // constant speed 3: the maximum is attained everywhere
  cruise.duration = 4.0;
  cruise.coeffs.col(1) = Vector3d(3.0, 0.0, 0.0);
  EXPECT_NEAR(mmh::bernsteinMaxDerivativeNorm(cruise, 1), 3.0, 1e-9);
  EXPECT_NEAR(mmh::bernsteinMaxDerivativeNorm(cruise, 2), 0.0, 1e-9);
  mmh::Piece seven;
  seven.duration = 1.3;
  seven.coeffs.col(7) = Vector3d(0.3, -0.2, 0.1);
  seven.coeffs.col(2) = Vector3d(1.0, 0.5, 0.0);
  const mmh::Trajectory t({seven});
  EXPECT_NEAR(mmh::bernsteinMaxDerivativeNorm(seven, 1), t.maxSpeed(), 1e-8);
  EXPECT_NEAR(mmh::bernsteinMaxDerivativeNorm(seven, 2), t.maxAcceleration(), 1e-8);
}

TEST(SpeedProfile, TrapezoidTriangleAndTurnAround) {
  using mmh::fpm::ProfileSpec;
  using mmh::fpm::SpeedProfile;
  ProfileSpec spec;
  spec.length = 40.0;
  const SpeedProfile trap = SpeedProfile::restToTarget(spec);
  EXPECT_NEAR(trap.duration(), 40.0 / 3.0 + 1.5, 1e-9);  // the bound of docs/benchmark.md
  EXPECT_NEAR(trap.positionAt(trap.duration()), 40.0, 1e-9);
  spec.length = 2.0;  // triangle: never reaches v_max
  const SpeedProfile tri = SpeedProfile::restToTarget(spec);
  EXPECT_NEAR(tri.duration(), 2.0, 1e-9);
  spec.length = 1.0;  // 3 m/s with 1 m to go: brakes past the target and comes back
  spec.u0 = 3.0;
  const SpeedProfile back = SpeedProfile::restToTarget(spec);
  EXPECT_NEAR(back.positionAt(back.duration()), 1.0, 1e-9);
  EXPECT_NEAR(back.speedAt(back.duration()), 0.0, 1e-9);
  double furthest = 0.0;
  for (double t = 0.0; t < back.duration(); t += 0.01)
    furthest = std::max(furthest, back.positionAt(t));
  EXPECT_NEAR(furthest, 9.0 / 4.0, 1e-3);  // braking distance at 2 m/s^2
}

TEST(SpeedProfile, SmoothedProfileKeepsTheLimitsAndHitsTheEnds) {
  using mmh::fpm::ProfileSpec;
  using mmh::fpm::SmoothProfile;
  for (double u0 : {0.0, 1.0, 3.0, -1.5}) {
    for (double length : {0.5, 3.0, 15.0, 40.0}) {
      ProfileSpec spec;
      spec.length = length;
      spec.u0 = u0;
      const SmoothProfile p = SmoothProfile::restToTarget(spec, 0.126);
      const auto s0 = p.state(0.0), s1 = p.state(p.duration());
      EXPECT_NEAR(s0.s, 0.0, 1e-9);
      EXPECT_NEAR(s0.v, u0, 1e-9);
      EXPECT_NEAR(s0.a, 0.0, 1e-9);
      EXPECT_NEAR(s1.s, length, 1e-6) << u0 << " " << length;
      EXPECT_NEAR(s1.v, 0.0, 1e-9);
      EXPECT_NEAR(s1.a, 0.0, 1e-9);
      for (double t = 0.0; t <= p.duration(); t += 0.002) {
        const auto st = p.state(t);
        EXPECT_LE(std::abs(st.v), std::max(3.0, std::abs(u0)) + 1e-9);
        EXPECT_LE(std::abs(st.a), 2.0 + 1e-9);
      }
      // Continuous (the knots between the polynomial stretches match).
      for (double k : p.kinks()) {
        const auto a = p.state(k - 1e-7), b = p.state(k + 1e-7);
        EXPECT_NEAR(a.s, b.s, 1e-6);
        EXPECT_NEAR(a.v, b.v, 1e-5);
        EXPECT_NEAR(a.a, b.a, 1e-4);
      }
    }
  }
}

TEST(SpeedProfile, EarlySpeedCapHoldsUntilItsTime) {
  mmh::fpm::ProfileSpec spec;
  spec.length = 30.0;
  spec.early_time = 2.0;
  spec.early_v_max = 1.5;
  const auto p = mmh::fpm::SpeedProfile::restToTarget(spec);
  for (double t = 0.0; t < 2.0; t += 0.01) EXPECT_LE(p.speedAt(t), 1.5 + 1e-9);
  double top = 0.0;
  for (double t = 2.0; t < p.duration(); t += 0.01) top = std::max(top, p.speedAt(t));
  EXPECT_NEAR(top, 3.0, 1e-9);
  EXPECT_NEAR(p.positionAt(p.duration()), 30.0, 1e-9);
}
