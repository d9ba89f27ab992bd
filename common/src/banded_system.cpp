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
      for (int j = 1; j <= j_end - k; ++j) row_i[j] -= l * row_k[j];
    }
  }
}

void BandedSystem::solve(Eigen::Ref<Eigen::MatrixXd> b) const {
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

void BandedSystem::solveTransposed(Eigen::Ref<Eigen::MatrixXd> b) const {
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

}  // namespace mmh
