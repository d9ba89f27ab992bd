#include "mmh/common/banded_system.hpp"

#include <algorithm>

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
      if (span == 6) {  // every row but the last six of MINCO's band: a fixed, unrolled length
        for (int j = 1; j <= 6; ++j) row_i[j] -= l * row_k[j];
      } else {
        for (int j = 1; j <= span; ++j) row_i[j] -= l * row_k[j];
      }
    }
  }
}

void BandedSystem::solve(Eigen::Ref<Eigen::MatrixXd> b) const {
  if (b.cols() == 3) return solve3(b.data(), b.outerStride());
  const int cols = static_cast<int>(b.cols());
  const Eigen::Index ld = b.outerStride();
  double* x = b.data();
  for (int j = 0; j < n_; ++j) {  // L y = b (unit lower)
    const int i_end = std::min(j + lower_, n_ - 1);
    for (int i = j + 1; i <= i_end; ++i) {
      const double l = (*this)(i, j);
      if (l == 0.0) continue;
      for (int c = 0; c < cols; ++c) x[c * ld + i] -= l * x[c * ld + j];
    }
  }
  for (int j = n_ - 1; j >= 0; --j) {  // U x = y
    const double inv = 1.0 / (*this)(j, j);
    for (int c = 0; c < cols; ++c) x[c * ld + j] *= inv;
    const int i_begin = std::max(0, j - upper_);
    for (int i = i_begin; i < j; ++i) {
      const double u = (*this)(i, j);
      if (u == 0.0) continue;
      for (int c = 0; c < cols; ++c) x[c * ld + i] -= u * x[c * ld + j];
    }
  }
}

// The same operations in the same order as the general loop, for the three axes of a
// trajectory (every MINCO solve): the columns as three pointers, the band walked by a pointer
// that steps one row down and one column left (A(i + 1, j) is w - 1 entries after A(i, j)).
void BandedSystem::solve3(double* x0, Eigen::Index ld) const {
  double* x1 = x0 + ld;
  double* x2 = x1 + ld;
  const double* a = band_.data();
  const int w = lower_ + upper_ + 1;
  for (int j = 0; j < n_; ++j) {  // L y = b (unit lower)
    const int i_end = std::min(j + lower_, n_ - 1);
    const double y0 = x0[j], y1 = x1[j], y2 = x2[j];
    const double* l = a + index(j, j);
    for (int i = j + 1; i <= i_end; ++i) {
      l += w - 1;
      if (*l == 0.0) continue;
      x0[i] -= *l * y0;
      x1[i] -= *l * y1;
      x2[i] -= *l * y2;
    }
  }
  for (int j = n_ - 1; j >= 0; --j) {  // U x = y
    const double inv = 1.0 / a[index(j, j)];
    const double y0 = (x0[j] *= inv), y1 = (x1[j] *= inv), y2 = (x2[j] *= inv);
    const int i_begin = std::max(0, j - upper_);
    const double* u = a + index(i_begin, j);
    for (int i = i_begin; i < j; ++i, u += w - 1) {
      if (*u == 0.0) continue;
      x0[i] -= *u * y0;
      x1[i] -= *u * y1;
      x2[i] -= *u * y2;
    }
  }
}

void BandedSystem::solveTransposed(Eigen::Ref<Eigen::MatrixXd> b) const {
  if (b.cols() == 3) return solveTransposed3(b.data(), b.outerStride());
  const int cols = static_cast<int>(b.cols());
  const Eigen::Index ld = b.outerStride();
  double* x = b.data();
  for (int j = 0; j < n_; ++j) {  // U^T z = b
    const int i_begin = std::max(0, j - upper_);
    for (int i = i_begin; i < j; ++i) {
      const double u = (*this)(i, j);
      if (u == 0.0) continue;
      for (int c = 0; c < cols; ++c) x[c * ld + j] -= u * x[c * ld + i];
    }
    const double inv = 1.0 / (*this)(j, j);
    for (int c = 0; c < cols; ++c) x[c * ld + j] *= inv;
  }
  for (int j = n_ - 1; j >= 0; --j) {  // L^T x = z
    const int i_end = std::min(j + lower_, n_ - 1);
    for (int i = j + 1; i <= i_end; ++i) {
      const double l = (*this)(i, j);
      if (l == 0.0) continue;
      for (int c = 0; c < cols; ++c) x[c * ld + j] -= l * x[c * ld + i];
    }
  }
}

// solveTransposed for three columns, as solve3: the same operations in the same order.
void BandedSystem::solveTransposed3(double* x0, Eigen::Index ld) const {
  double* x1 = x0 + ld;
  double* x2 = x1 + ld;
  const double* a = band_.data();
  const int w = lower_ + upper_ + 1;
  for (int j = 0; j < n_; ++j) {  // U^T z = b
    const int i_begin = std::max(0, j - upper_);
    double z0 = x0[j], z1 = x1[j], z2 = x2[j];
    const double* u = a + index(i_begin, j);
    for (int i = i_begin; i < j; ++i, u += w - 1) {
      if (*u == 0.0) continue;
      z0 -= *u * x0[i];
      z1 -= *u * x1[i];
      z2 -= *u * x2[i];
    }
    const double inv = 1.0 / a[index(j, j)];
    x0[j] = z0 * inv;
    x1[j] = z1 * inv;
    x2[j] = z2 * inv;
  }
  for (int j = n_ - 1; j >= 0; --j) {  // L^T x = z
    const int i_end = std::min(j + lower_, n_ - 1);
    double z0 = x0[j], z1 = x1[j], z2 = x2[j];
    const double* l = a + index(j, j);
    for (int i = j + 1; i <= i_end; ++i) {
      l += w - 1;
      if (*l == 0.0) continue;
      z0 -= *l * x0[i];
      z1 -= *l * x1[i];
      z2 -= *l * x2[i];
    }
    x0[j] = z0;
    x1[j] = z1;
    x2[j] = z2;
  }
}

}  // namespace mmh
