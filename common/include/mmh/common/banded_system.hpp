// Square banded linear system solved by LU factorisation without pivoting, O(n (p+q)^2):
// what makes MINCO linear-time in the number of pieces.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace mmh {

class BandedSystem {
 public:
  // n x n matrix with `lower` sub-diagonals and `upper` super-diagonals, all zero.
  void create(int n, int lower, int upper);
  void reset();  // zero all entries, keep the shape
  double& operator()(int i, int j) { return band_[index(i, j)]; }
  double operator()(int i, int j) const { return band_[index(i, j)]; }
  int size() const { return n_; }

  // In-place LU; the matrix must not need pivoting (MINCO's ordering guarantees non-zero pivots).
  void factorize();
  // Solve A X = B (or A^T X = B) in place for each column of B, after factorize().
  void solve(Eigen::Ref<Eigen::MatrixXd> b) const;
  void solveTransposed(Eigen::Ref<Eigen::MatrixXd> b) const;

 private:
  // kCols columns starting at x, ld apart.
  template <int kCols>
  void solveColumns(double* x, Eigen::Index ld) const;
  template <int kCols>
  void solveTransposedColumns(double* x, Eigen::Index ld) const;
  // Row-major band: row i keeps columns i - lower .. i + upper contiguously (cache-friendly
  // row operations in the factorisation and the solves).
  int index(int i, int j) const { return i * (lower_ + upper_ + 1) + (j - i + lower_); }
  int n_ = 0, lower_ = 0, upper_ = 0;
  std::vector<double> band_;
};

}  // namespace mmh
