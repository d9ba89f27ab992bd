#include "mmh/arbiter/stopping_trajectory.hpp"

#include <algorithm>
#include <cmath>

#include "mmh/common/minco.hpp"

namespace mmh::arbiter {

Trajectory makeStoppingTrajectory(const KinematicState& start, double max_acc_mps2,
                                  double max_vel_mps) {
  const double speed = start.velocity.norm();
  if (speed < 1e-3 && start.acceleration.norm() < 1e-3) {
    Piece hold;
    hold.duration = 1.0;
    hold.coeffs.col(0) = start.position;
    return Trajectory({hold});
  }
  // Three minimum-jerk pieces whose junctions follow a constant deceleration: close to the
  // bang-bang stop, with bounded jerk. Lengthen the stop until the exact maxima fit the limits.
  const Eigen::Vector3d dir =
      speed > 1e-6 ? Eigen::Vector3d(start.velocity / speed) : Eigen::Vector3d::Zero();
  const double speed_limit = std::max(max_vel_mps, speed);
  Trajectory best;
  for (double total = std::max(0.2, 1.05 * speed / max_acc_mps2);; total *= 1.08) {
    const double decel = speed / total;
    MincoJerk minco;
    Eigen::Matrix3d head, tail;
    head << start.position, start.velocity, start.acceleration;
    const double stop_dist = 0.5 * speed * total;
    tail << start.position + dir * stop_dist, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero();
    const int pieces = 3;
    minco.setConditions(head, tail, pieces);
    Eigen::Matrix3Xd inner(3, pieces - 1);
    for (int i = 1; i < pieces; ++i) {
      const double t = total * i / pieces;
      inner.col(i - 1) = start.position + dir * (speed * t - 0.5 * decel * t * t);
    }
    minco.setParameters(inner, Eigen::VectorXd::Constant(pieces, total / pieces));
    best = minco.trajectory();
    if ((best.maxAcceleration() <= max_acc_mps2 && best.maxSpeed() <= speed_limit * 1.0001) ||
        total > 60.0) {
      return best;
    }
  }
}

}  // namespace mmh::arbiter
