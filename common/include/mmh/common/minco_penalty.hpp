// Time integral of a pointwise constraint penalty over a MINCO trajectory, by the trapezoid
// rule on `samples_per_piece` intervals, with its gradient w.r.t. coefficients and durations.
// The penalty functor decides what is penalised (speed, acceleration, corridor, ...).
#pragma once

#include <Eigen/Core>

#include "mmh/common/minco.hpp"

namespace mmh {

struct PenaltyPoint {
  int piece;     // piece index
  double t;      // local time in the piece
  double alpha;  // t / T_piece
  Eigen::Vector3d pos, vel, acc, jerk;
};

// penalty(point, grad_pos, grad_vel, grad_acc) -> value; the gradients are set by the functor
// (they start at zero).
template <typename Penalty>
double integratePenalty(const MincoJerk& minco, int samples_per_piece, Penalty&& penalty,
                        Eigen::MatrixX3d& grad_coeffs, Eigen::VectorXd& grad_durations) {
  const Eigen::MatrixX3d& c = minco.coeffs();
  const Eigen::VectorXd& durations = minco.durations();
  double total = 0.0;
  Eigen::Matrix<double, 6, 1> b0, b1, b2;  // bases of position .. acceleration at t
  for (int i = 0; i < minco.numPieces(); ++i) {
    // Coefficient rows of piece i (ascending powers), one column per axis.
    const Eigen::Matrix<double, 6, 3> ci = c.block<6, 3>(6 * i, 0);
    const Eigen::RowVector3d k0 = ci.row(0), k1 = ci.row(1), k2 = ci.row(2), k3 = ci.row(3),
                             k4 = ci.row(4), k5 = ci.row(5);
    const double step = durations[i] / samples_per_piece;
    for (int j = 0; j <= samples_per_piece; ++j) {
      const double t = j * step;
      // Horner evaluation of the state; the bases are built only where the penalty is active.
      PenaltyPoint point{
          i,
          t,
          static_cast<double>(j) / samples_per_piece,
          (k0 + t * (k1 + t * (k2 + t * (k3 + t * (k4 + t * k5))))).transpose(),
          (k1 + t * (2.0 * k2 + t * (3.0 * k3 + t * (4.0 * k4 + t * 5.0 * k5)))).transpose(),
          (2.0 * k2 + t * (6.0 * k3 + t * (12.0 * k4 + t * 20.0 * k5))).transpose(),
          (6.0 * k3 + t * (24.0 * k4 + t * 60.0 * k5)).transpose()};
      Eigen::Vector3d gp = Eigen::Vector3d::Zero(), gv = Eigen::Vector3d::Zero(),
                      ga = Eigen::Vector3d::Zero();
      const double value = penalty(point, gp, gv, ga);
      if (value == 0.0 && gp.isZero() && gv.isZero() && ga.isZero()) continue;
      const double t2 = t * t, t3 = t2 * t, t4 = t3 * t, t5 = t4 * t;
      b0 << 1.0, t, t2, t3, t4, t5;
      b1 << 0.0, 1.0, 2.0 * t, 3.0 * t2, 4.0 * t3, 5.0 * t4;
      b2 << 0.0, 0.0, 2.0, 6.0 * t, 12.0 * t2, 20.0 * t3;
      const double weight = (j == 0 || j == samples_per_piece) ? 0.5 : 1.0;
      const double scale = weight * step;
      grad_coeffs.block<6, 3>(6 * i, 0) +=
          scale * (b0 * gp.transpose() + b1 * gv.transpose() + b2 * ga.transpose());
      // d/dT of (step * f(p(alpha T))) = f / K + step * alpha * (grad f . d/dt state).
      grad_durations[i] +=
          weight *
          (value / samples_per_piece +
           step * point.alpha * (gp.dot(point.vel) + gv.dot(point.acc) + ga.dot(point.jerk)));
      total += scale * value;
    }
  }
  return total;
}

}  // namespace mmh
