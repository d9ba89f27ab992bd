#include "mmh/common/minco.hpp"

#include <cassert>

namespace mmh {

// Row layout (M pieces, unknowns: 6 coefficients per piece, piece i in columns 6i..6i+5):
//   rows 0..2            head position, velocity, acceleration of piece 0 at t = 0
//   for each junction i (end of piece i, start of piece i+1), rows 6i+3 .. 6i+8:
//     jerk continuity, snap continuity, position = q_i, position / velocity / acceleration
//     continuity
//   rows 6M-3 .. 6M-1    tail position, velocity, acceleration of piece M-1 at T_{M-1}
// This ordering keeps every pivot non-zero, so the banded LU needs no pivoting.

void MincoJerk::setConditions(const Eigen::Matrix3d& head, const Eigen::Matrix3d& tail,
                              int pieces) {
  assert(pieces >= 1);
  pieces_ = pieces;
  head_ = head;
  tail_ = tail;
  system_.create(6 * pieces, 6, 6);
  coeffs_.setZero(6 * pieces, 3);
}

void MincoJerk::assemble(BandedSystem& a) const {
  a.reset();
  a(0, 0) = 1.0;
  a(1, 1) = 1.0;
  a(2, 2) = 2.0;
  for (int i = 0; i < pieces_ - 1; ++i) {
    const double t1 = durations_[i], t2 = t1 * t1, t3 = t2 * t1, t4 = t3 * t1, t5 = t4 * t1;
    const int r = 6 * i + 3, c = 6 * i;
    a(r, c + 3) = 6.0;  // jerk continuity
    a(r, c + 4) = 24.0 * t1;
    a(r, c + 5) = 60.0 * t2;
    a(r, c + 9) = -6.0;
    a(r + 1, c + 4) = 24.0;  // snap continuity
    a(r + 1, c + 5) = 120.0 * t1;
    a(r + 1, c + 10) = -24.0;
    const double pos[6] = {1.0, t1, t2, t3, t4, t5};
    for (int k = 0; k < 6; ++k) {
      a(r + 2, c + k) = pos[k];  // position = q_i
      a(r + 3, c + k) = pos[k];  // position continuity
    }
    a(r + 3, c + 6) = -1.0;
    const double vel[5] = {1.0, 2.0 * t1, 3.0 * t2, 4.0 * t3, 5.0 * t4};
    for (int k = 0; k < 5; ++k) a(r + 4, c + 1 + k) = vel[k];
    a(r + 4, c + 7) = -1.0;
    const double acc[4] = {2.0, 6.0 * t1, 12.0 * t2, 20.0 * t3};
    for (int k = 0; k < 4; ++k) a(r + 5, c + 2 + k) = acc[k];
    a(r + 5, c + 8) = -2.0;
  }
  const double t1 = durations_[pieces_ - 1], t2 = t1 * t1, t3 = t2 * t1, t4 = t3 * t1, t5 = t4 * t1;
  const int r = 6 * pieces_ - 3, c = 6 * (pieces_ - 1);
  const double pos[6] = {1.0, t1, t2, t3, t4, t5};
  for (int k = 0; k < 6; ++k) a(r, c + k) = pos[k];
  const double vel[5] = {1.0, 2.0 * t1, 3.0 * t2, 4.0 * t3, 5.0 * t4};
  for (int k = 0; k < 5; ++k) a(r + 1, c + 1 + k) = vel[k];
  const double acc[4] = {2.0, 6.0 * t1, 12.0 * t2, 20.0 * t3};
  for (int k = 0; k < 4; ++k) a(r + 2, c + 2 + k) = acc[k];
}

Eigen::MatrixX3d MincoJerk::rightHandSide() const {
  Eigen::MatrixX3d b = Eigen::MatrixX3d::Zero(6 * pieces_, 3);
  b.topRows(3) = head_.transpose();
  for (int i = 0; i < pieces_ - 1; ++i) b.row(6 * i + 5) = points_.col(i).transpose();
  b.bottomRows(3) = tail_.transpose();
  return b;
}

void MincoJerk::setParameters(const Eigen::Matrix3Xd& inner_points,
                              const Eigen::VectorXd& durations) {
  assert(inner_points.cols() == pieces_ - 1 && durations.size() == pieces_);
  points_ = inner_points;
  durations_ = durations;
  assemble(system_);
  system_.factorize();
  coeffs_ = rightHandSide();
  system_.solve(coeffs_);
}

Trajectory MincoJerk::trajectory() const {
  Trajectory traj;
  for (int i = 0; i < pieces_; ++i) {
    Piece piece;
    piece.duration = durations_[i];
    piece.coeffs.leftCols(6) = coeffs_.block<6, 3>(6 * i, 0).transpose();
    traj.append(piece);
  }
  return traj;
}

double MincoJerk::energy() const {
  double e = 0.0;
  for (int i = 0; i < pieces_; ++i) {
    const Eigen::Vector3d c3 = coeffs_.row(6 * i + 3), c4 = coeffs_.row(6 * i + 4),
                          c5 = coeffs_.row(6 * i + 5);
    const double t1 = durations_[i], t2 = t1 * t1, t3 = t2 * t1, t4 = t3 * t1, t5 = t4 * t1;
    e += 36.0 * c3.squaredNorm() * t1 + 144.0 * c3.dot(c4) * t2 + 192.0 * c4.squaredNorm() * t3 +
         240.0 * c3.dot(c5) * t3 + 720.0 * c4.dot(c5) * t4 + 720.0 * c5.squaredNorm() * t5;
  }
  return e;
}

void MincoJerk::addEnergyGradient(Eigen::MatrixX3d& grad_coeffs,
                                  Eigen::VectorXd& grad_durations) const {
  for (int i = 0; i < pieces_; ++i) {
    const Eigen::RowVector3d c3 = coeffs_.row(6 * i + 3), c4 = coeffs_.row(6 * i + 4),
                             c5 = coeffs_.row(6 * i + 5);
    const double t1 = durations_[i], t2 = t1 * t1, t3 = t2 * t1, t4 = t3 * t1, t5 = t4 * t1;
    grad_coeffs.row(6 * i + 3) += 72.0 * c3 * t1 + 144.0 * c4 * t2 + 240.0 * c5 * t3;
    grad_coeffs.row(6 * i + 4) += 144.0 * c3 * t2 + 384.0 * c4 * t3 + 720.0 * c5 * t4;
    grad_coeffs.row(6 * i + 5) += 240.0 * c3 * t3 + 720.0 * c4 * t4 + 1440.0 * c5 * t5;
    grad_durations[i] += 36.0 * c3.squaredNorm() + 288.0 * c3.dot(c4) * t1 +
                         576.0 * c4.squaredNorm() * t2 + 720.0 * c3.dot(c5) * t2 +
                         2880.0 * c4.dot(c5) * t3 + 3600.0 * c5.squaredNorm() * t4;
  }
}

void MincoJerk::propagateGradient(Eigen::MatrixX3d& grad_coeffs,
                                  const Eigen::VectorXd& grad_durations,
                                  Eigen::Matrix3Xd& grad_points,
                                  Eigen::VectorXd& grad_total_durations) const {
  // Adjoint: G = A^{-T} dK/dc. Then dK/db = G and dK/dT_i = explicit - G^T (dA/dT_i) c.
  system_.solveTransposed(grad_coeffs);
  const Eigen::MatrixX3d& g = grad_coeffs;
  grad_points.resize(3, pieces_ - 1);
  grad_total_durations = grad_durations;
  for (int i = 0; i < pieces_; ++i) {
    const Eigen::RowVector3d c1 = coeffs_.row(6 * i + 1), c2 = coeffs_.row(6 * i + 2),
                             c3 = coeffs_.row(6 * i + 3), c4 = coeffs_.row(6 * i + 4),
                             c5 = coeffs_.row(6 * i + 5);
    const double t1 = durations_[i], t2 = t1 * t1, t3 = t2 * t1, t4 = t3 * t1;
    // Derivatives of piece i at its end: d/dT of each row's left-hand side.
    const Eigen::RowVector3d vel =
        c1 + 2.0 * c2 * t1 + 3.0 * c3 * t2 + 4.0 * c4 * t3 + 5.0 * c5 * t4;
    const Eigen::RowVector3d acc = 2.0 * c2 + 6.0 * c3 * t1 + 12.0 * c4 * t2 + 20.0 * c5 * t3;
    const Eigen::RowVector3d jerk = 6.0 * c3 + 24.0 * c4 * t1 + 60.0 * c5 * t2;
    if (i < pieces_ - 1) {
      const int r = 6 * i + 3;
      const Eigen::RowVector3d snap = 24.0 * c4 + 120.0 * c5 * t1;
      const Eigen::RowVector3d crackle = 120.0 * c5;
      grad_points.col(i) = g.row(r + 2).transpose();
      grad_total_durations[i] -= g.row(r).dot(snap) + g.row(r + 1).dot(crackle) +
                                 g.row(r + 2).dot(vel) + g.row(r + 3).dot(vel) +
                                 g.row(r + 4).dot(acc) + g.row(r + 5).dot(jerk);
    } else {
      const int r = 6 * pieces_ - 3;
      grad_total_durations[i] -= g.row(r).dot(vel) + g.row(r + 1).dot(acc) + g.row(r + 2).dot(jerk);
    }
  }
}

Eigen::MatrixXd MincoJerk::denseMatrix() const {
  BandedSystem a;
  a.create(6 * pieces_, 6, 6);
  assemble(a);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(6 * pieces_, 6 * pieces_);
  for (int i = 0; i < 6 * pieces_; ++i)
    for (int j = std::max(0, i - 6); j <= std::min(6 * pieces_ - 1, i + 6); ++j)
      dense(i, j) = a(i, j);
  return dense;
}

}  // namespace mmh
