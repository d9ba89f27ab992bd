#include "mmh/common/banded_system.hpp"

#include <algorithm>
#include <type_traits>

namespace mmh {

void BandedSystem::create(int n, int lower, int upper) {
  n_ = n;
  lower_ = lower;
  upper_ = upper;
  band_.assign(static_cast<size_t>(n) * (lower + upper + 1), 0.0);
}

void BandedSystem::reset() {
  std::fill(band_.begin(), band_.end(), 0.0);
}

void BandedSystem::factorize() {
  double* a = band_.data();
  for (int k = 0; k < n_; ++k) {
    const int i_end = std::min(k + lower_, n_ - 1);
    const int j_end = std::min(k + upper_, n_ - 1);
    const double* row_k = a + index(k, k);  // row_k[j - k] = A(k, j)
    const double pivot = row_k[0];
    for (int i = k + 1; i <= i_end; ++i) {
      double* row_i = a + index(i, k);  // row_i[j - k] = A(i, j)
      if (row_i[0] == 0.0) continue;
      const double l = row_i[0] / pivot;
      row_i[0] = l;
      const int span = j_end - k;
      if (span == 6) {  // interior rows of a band six wide above the diagonal (MINCO's): unrolled
        for (int j = 1; j <= 6; ++j) row_i[j] -= l * row_k[j];
      } else {
        for (int j = 1; j <= span; ++j) row_i[j] -= l * row_k[j];
      }
    }
  }
}

// Columns are independent: they are solved in groups of at most three (a trajectory's three
// axes in one pass), each group through one pointer per column, the band walked by a pointer
// that steps one row down and one column left (A(i + 1, j) is w - 1 entries after A(i, j)).
// Every entry sees the same operations in the same order whatever the grouping.
template <int kCols>
void BandedSystem::solveColumns(double* x, Eigen::Index ld) const {
  double* col[kCols];
  for (int c = 0; c < kCols; ++c) col[c] = x + c * ld;
  const double* a = band_.data();
  const int w = lower_ + upper_ + 1;
  for (int j = 0; j < n_; ++j) {  // L y = b (unit lower)
    const int i_end = std::min(j + lower_, n_ - 1);
    double y[kCols];
    for (int c = 0; c < kCols; ++c) y[c] = col[c][j];
    const double* l = a + index(j, j);
    for (int i = j + 1; i <= i_end; ++i) {
      l += w - 1;
      if (*l == 0.0) continue;
      for (int c = 0; c < kCols; ++c) col[c][i] -= *l * y[c];
    }
  }
  for (int j = n_ - 1; j >= 0; --j) {  // U x = y
    const double inv = 1.0 / a[index(j, j)];
    double y[kCols];
    for (int c = 0; c < kCols; ++c) y[c] = (col[c][j] *= inv);
    const int i_begin = std::max(0, j - upper_);
    const double* u = a + index(i_begin, j);
    for (int i = i_begin; i < j; ++i, u += w - 1) {
      if (*u == 0.0) continue;
      for (int c = 0; c < kCols; ++c) col[c][i] -= *u * y[c];
    }
  }
}

template <int kCols>
void BandedSystem::solveTransposedColumns(double* x, Eigen::Index ld) const {
  double* col[kCols];
  for (int c = 0; c < kCols; ++c) col[c] = x + c * ld;
  const double* a = band_.data();
  const int w = lower_ + upper_ + 1;
  for (int j = 0; j < n_; ++j) {  // U^T z = b
    const int i_begin = std::max(0, j - upper_);
    double z[kCols];
    for (int c = 0; c < kCols; ++c) z[c] = col[c][j];
    const double* u = a + index(i_begin, j);
    for (int i = i_begin; i < j; ++i, u += w - 1) {
      if (*u == 0.0) continue;
      for (int c = 0; c < kCols; ++c) z[c] -= *u * col[c][i];
    }
    const double inv = 1.0 / a[index(j, j)];
    for (int c = 0; c < kCols; ++c) col[c][j] = z[c] * inv;
  }
  for (int j = n_ - 1; j >= 0; --j) {  // L^T x = z
    const int i_end = std::min(j + lower_, n_ - 1);
    double z[kCols];
    for (int c = 0; c < kCols; ++c) z[c] = col[c][j];
    const double* l = a + index(j, j);
    for (int i = j + 1; i <= i_end; ++i) {
      l += w - 1;
      if (*l == 0.0) continue;
      for (int c = 0; c < kCols; ++c) z[c] -= *l * col[c][i];
    }
    for (int c = 0; c < kCols; ++c) col[c][j] = z[c];
  }
}

namespace {

// Calls solve(std::integral_constant<int, k>, first column, stride) for b's columns in groups of
// k <= 3.
template <typename Solve>
void forColumnGroups(Eigen::Ref<Eigen::MatrixXd> b, const Solve& solve) {
  const Eigen::Index ld = b.outerStride();
  for (Eigen::Index c = 0; c < b.cols(); c += 3) {
    double* x = b.data() + c * ld;
    switch (std::min<Eigen::Index>(3, b.cols() - c)) {
      case 3:
        solve(std::integral_constant<int, 3>{}, x, ld);
        break;
      case 2:
        solve(std::integral_constant<int, 2>{}, x, ld);
        break;
      default:
        solve(std::integral_constant<int, 1>{}, x, ld);
        break;
    }
  }
}

}  // namespace

void BandedSystem::solve(Eigen::Ref<Eigen::MatrixXd> b) const {
  forColumnGroups(b, [this](auto cols, double* x, Eigen::Index ld) {
    solveColumns<decltype(cols)::value>(x, ld);
  });
}

void BandedSystem::solveTransposed(Eigen::Ref<Eigen::MatrixXd> b) const {
  forColumnGroups(b, [this](auto cols, double* x, Eigen::Index ld) {
    solveTransposedColumns<decltype(cols)::value>(x, ld);
  });
}

}  // namespace mmh
