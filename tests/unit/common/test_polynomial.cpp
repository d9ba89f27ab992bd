#include <gtest/gtest.h>

#include <cmath>

#include "mmh/common/polynomial.hpp"

using mmh::PolyCoeffs;

TEST(Polynomial, EvalDerivativeIntegral) {
  PolyCoeffs c(4);
  c << 1.0, -2.0, 0.5, 3.0;  // 1 - 2t + 0.5t^2 + 3t^3
  EXPECT_DOUBLE_EQ(mmh::polyEval(c, 2.0), 1 - 4 + 2 + 24);
  PolyCoeffs d = mmh::polyDerivative(c);  // -2 + t + 9t^2
  EXPECT_DOUBLE_EQ(mmh::polyEval(d, 2.0), -2 + 2 + 36);
  // integral_0^2 = 2 - 4 + 0.5*8/3 + 3*16/4
  EXPECT_NEAR(mmh::polyIntegral(c, 2.0), 2 - 4 + 4.0 / 3.0 + 12, 1e-12);
}

TEST(Polynomial, RealRootsOfKnownProduct) {
  // (t - 0.3)(t - 1.1)(t - 2.5)(t + 1) : three roots in [0, 3], one outside.
  PolyCoeffs p = PolyCoeffs::Ones(1);
  for (double r : {0.3, 1.1, 2.5, -1.0}) {
    PolyCoeffs f(2);
    f << -r, 1.0;
    p = mmh::polyMultiply(p, f);
  }
  auto roots = mmh::polyRealRoots(p, 0.0, 3.0);
  ASSERT_EQ(roots.size(), 3u);
  EXPECT_NEAR(roots[0], 0.3, 1e-10);
  EXPECT_NEAR(roots[1], 1.1, 1e-10);
  EXPECT_NEAR(roots[2], 2.5, 1e-10);
}

TEST(Polynomial, CloseRootsAreNotMissed) {
  // Two roots 1e-4 apart: a sampling check at 1e-3 would miss the dip below zero.
  PolyCoeffs p(3);
  const double a = 1.0, b = 1.0001;
  p << a * b, -(a + b), 1.0;
  auto roots = mmh::polyRealRoots(p, 0.0, 2.0);
  ASSERT_EQ(roots.size(), 2u);
  EXPECT_NEAR(roots[0], a, 1e-9);
  EXPECT_NEAR(roots[1], b, 1e-9);
}

TEST(Polynomial, MaxOnIntervalFindsInteriorPeak) {
  PolyCoeffs p(3);
  p << 0.0, 4.0, -1.0;  // 4t - t^2, max 4 at t = 2
  double arg = 0;
  EXPECT_NEAR(mmh::polyMaxOnInterval(p, 0.0, 5.0, &arg), 4.0, 1e-12);
  EXPECT_NEAR(arg, 2.0, 1e-9);
  EXPECT_NEAR(mmh::polyMaxOnInterval(p, 3.0, 5.0), 3.0, 1e-12);  // end point
}
