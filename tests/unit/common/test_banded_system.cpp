// The banded LU behind MINCO: its solves against a dense solve, and the three-column solves
// (every trajectory's three axes) against the general loop, to the last bit.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "mmh/common/banded_system.hpp"

namespace {

// A random diagonally dominant band matrix (no pivoting needed) with some zeros in the band,
// as MINCO's has, and its dense copy.
struct Banded {
  mmh::BandedSystem system;
  Eigen::MatrixXd dense;
};

Banded randomBanded(int n, int lower, int upper, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Banded b;
  b.system.create(n, lower, upper);
  b.dense = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = std::max(0, i - lower); j <= std::min(n - 1, i + upper); ++j) {
      double v = u(rng);
      if (i != j && v > 0.6) v = 0.0;  // structural zeros the solves skip
      if (i == j) v = (v >= 0.0 ? 1.0 : -1.0) * (lower + upper + 2.0);
      b.system(i, j) = v;
      b.dense(i, j) = v;
    }
  return b;
}

Eigen::MatrixXd randomColumns(int n, int cols, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  return Eigen::MatrixXd::NullaryExpr(n, cols, [&](Eigen::Index, Eigen::Index) { return u(rng); });
}

TEST(BandedSystem, SolvesMatchADenseSolve) {
  for (int cols : {1, 2, 3, 4}) {
    Banded b = randomBanded(60, 6, 6, 7u + cols);
    b.system.factorize();
    const Eigen::MatrixXd rhs = randomColumns(60, cols, 11u + cols);
    Eigen::MatrixXd x = rhs, xt = rhs;
    b.system.solve(x);
    b.system.solveTransposed(xt);
    EXPECT_LT((x - b.dense.partialPivLu().solve(rhs)).norm(), 1e-10 * rhs.norm()) << cols;
    EXPECT_LT((xt - b.dense.transpose().partialPivLu().solve(rhs)).norm(), 1e-10 * rhs.norm())
        << cols;
  }
}

TEST(BandedSystem, ThreeColumnsGiveTheSameBitsAsOneColumnAtATime) {
  for (const auto& [n, lower, upper] : {std::tuple{60, 6, 6}, {7, 6, 6}, {30, 2, 4}}) {
    Banded b = randomBanded(n, lower, upper, 3u + n);
    b.system.factorize();
    const Eigen::MatrixXd rhs = randomColumns(n, 3, 5u + n);
    Eigen::MatrixXd together = rhs, together_t = rhs;
    b.system.solve(together);
    b.system.solveTransposed(together_t);
    for (int c = 0; c < 3; ++c) {
      Eigen::MatrixXd one = rhs.col(c), one_t = rhs.col(c);
      b.system.solve(one);
      b.system.solveTransposed(one_t);
      EXPECT_TRUE(together.col(c) == one.col(0)) << n << " column " << c;
      EXPECT_TRUE(together_t.col(c) == one_t.col(0)) << n << " column " << c;
    }
  }
}

}  // namespace
