#include "mmh/common/heading.hpp"

#include <algorithm>
#include <cmath>

namespace mmh {

double wrapAngle(double a) {
  return std::remainder(a, 2.0 * M_PI);
}

double turnTowards(double yaw, double target, double dt, const HeadingParams& params) {
  const double error = wrapAngle(target - yaw);
  const double max_rate = params.max_rate_dps * M_PI / 180.0;
  double change =
      params.time_constant_s > 0.0 ? error * std::min(1.0, dt / params.time_constant_s) : error;
  change = std::clamp(change, -max_rate * dt, max_rate * dt);
  return wrapAngle(yaw + change);
}

double followHeading(double yaw, const Trajectory& trajectory, double t,
                     const Eigen::Vector3d& position, double dt, const HeadingParams& params) {
  const double end_s = trajectory.duration();
  double ahead = std::max(0.0, std::min(t + params.lookahead_s, end_s));
  Eigen::Vector3d look = trajectory.position(ahead) - position;
  // Creeping: walk on along the trajectory, in steps of the look-ahead time, to a point far
  // enough away to show the direction of travel.
  const double step_s = std::max(0.05, params.lookahead_s);
  while (look.head<2>().norm() < params.min_lookahead_m && ahead < end_s) {
    ahead = std::min(ahead + step_s, end_s);
    look = trajectory.position(ahead) - position;
  }
  if (look.head<2>().norm() < 0.05) return yaw;
  return turnTowards(yaw, std::atan2(look.y(), look.x()), dt, params);
}

}  // namespace mmh
