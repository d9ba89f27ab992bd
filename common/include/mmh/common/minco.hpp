// MINCO minimum-jerk trajectory class (Wang et al., T-RO 2022): the quintic pieces that minimise
// the integral of |jerk|^2 for given intermediate waypoints q and durations T follow from a
// banded linear system in O(M); gradients of any cost on the coefficients propagate back to
// (q, T) through the same system. Used by FPM and SOM.
#pragma once

#include <Eigen/Core>

#include "mmh/common/banded_system.hpp"
#include "mmh/common/trajectory.hpp"

namespace mmh {

class MincoJerk {
 public:
  static constexpr int kCoeffsPerPiece = 6;

  // head / tail: columns position, velocity, acceleration. pieces >= 1.
  void setConditions(const Eigen::Matrix3d& head, const Eigen::Matrix3d& tail, int pieces);
  // inner_points: 3 x (pieces - 1); durations: pieces values > 0.
  void setParameters(const Eigen::Matrix3Xd& inner_points, const Eigen::VectorXd& durations);

  int numPieces() const { return pieces_; }
  const Eigen::VectorXd& durations() const { return durations_; }
  // Row block 6i..6i+5 holds piece i's coefficients c0..c5 (ascending powers), one column per axis.
  const Eigen::MatrixX3d& coeffs() const { return coeffs_; }
  Trajectory trajectory() const;

  // Integral of |jerk|^2 over all pieces.
  double energy() const;
  // Adds the partial derivatives of energy() w.r.t. the coefficients and the durations.
  void addEnergyGradient(Eigen::MatrixX3d& grad_coeffs, Eigen::VectorXd& grad_durations) const;

  // Chain rule through the linear system: from dK/dc (6M x 3) and the explicit dK/dT (M) to
  // dK/dq (3 x (M-1)) and the total dK/dT (M). grad_coeffs is used as workspace.
  void propagateGradient(Eigen::MatrixX3d& grad_coeffs, const Eigen::VectorXd& grad_durations,
                         Eigen::Matrix3Xd& grad_points,
                         Eigen::VectorXd& grad_total_durations) const;

  // The dense system matrix and right-hand side (for tests that check the banded solve).
  Eigen::MatrixXd denseMatrix() const;
  Eigen::MatrixX3d rightHandSide() const;

 private:
  void assemble(BandedSystem& a) const;

  int pieces_ = 0;
  Eigen::Matrix3d head_ = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d tail_ = Eigen::Matrix3d::Zero();
  Eigen::Matrix3Xd points_;
  Eigen::VectorXd durations_;
  BandedSystem system_;
  Eigen::MatrixX3d coeffs_;
};

}  // namespace mmh
