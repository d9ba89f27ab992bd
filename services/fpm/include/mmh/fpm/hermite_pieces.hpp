// Piecewise quintic trajectories given by their knot states: each piece is the unique quintic
// that matches position, velocity and acceleration at both of its ends over its duration (the
// "boundary conditions D_P and time allocation T" of paper eq. 1). Any such trajectory is
// continuous up to acceleration, and cubic pieces (constant jerk, as in S-curves) are included.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mmh/common/trajectory.hpp"

namespace mmh::fpm {

struct KnotState {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
};

// Columns c0..c5 (ascending powers of the local time) of the quintic from `from` to `to`.
using QuinticCoeffs = Eigen::Matrix<double, 3, 6>;
QuinticCoeffs hermiteQuintic(const KnotState& from, const KnotState& to, double duration);

// knots.size() == durations.size() + 1.
Trajectory hermiteTrajectory(const std::vector<KnotState>& knots, const Eigen::VectorXd& durations);

// Integral of |jerk|^2 over one quintic piece of the given duration.
double quinticJerkEnergy(const QuinticCoeffs& c, double duration);

}  // namespace mmh::fpm
