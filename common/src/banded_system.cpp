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
  for (int k = 0; k < n_; ++k) {
    const int i_end = std::min(k + lower_, n_ - 1);
    const int j_end = std::min(k + upper_, n_ - 1);
    const double pivot = (*this)(k, k);
    for (int i = k + 1; i <= i_end; ++i) {
      double& l = (*this)(i, k);
      if (l == 0.0) continue;
      l /= pivot;
      for (int j = k + 1; j <= j_end; ++j) (*this)(i, j) -= l * (*this)(k, j);
    }
  }
}

void BandedSystem::solve(Eigen::Ref<Eigen::MatrixXd> b) const {
  for (int j = 0; j < n_; ++j) {  // L y = b (unit lower)
    const int i_end = std::min(j + lower_, n_ - 1);
    for (int i = j + 1; i <= i_end; ++i) b.row(i) -= (*this)(i, j) * b.row(j);
  }
  for (int j = n_ - 1; j >= 0; --j) {  // U x = y
    b.row(j) /= (*this)(j, j);
    const int i_begin = std::max(0, j - upper_);
    for (int i = i_begin; i < j; ++i) b.row(i) -= (*this)(i, j) * b.row(j);
  }
}

void BandedSystem::solveTransposed(Eigen::Ref<Eigen::MatrixXd> b) const {
  for (int j = 0; j < n_; ++j) {  // U^T z = b
    const int i_begin = std::max(0, j - upper_);
    for (int i = i_begin; i < j; ++i) b.row(j) -= (*this)(i, j) * b.row(i);
    b.row(j) /= (*this)(j, j);
  }
  for (int j = n_ - 1; j >= 0; --j) {  // L^T x = z
    const int i_end = std::min(j + lower_, n_ - 1);
    for (int i = j + 1; i <= i_end; ++i) b.row(j) -= (*this)(i, j) * b.row(i);
  }
}

}  // namespace mmh
