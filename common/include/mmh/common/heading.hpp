// Heading of a multirotor that looks where it flies: the yaw turns towards the point
// lookahead_s ahead on the trajectory, through a first-order lag and a rate limit. The simulated
// vehicle's camera and mmh-setpoint's yaw setpoints both follow it.
#pragma once

#include <Eigen/Core>

#include "mmh/common/trajectory.hpp"

namespace mmh {

struct HeadingParams {
  double lookahead_s = 0.5;
  double time_constant_s = 0.2;  // first-order lag (0: none)
  double max_rate_dps = 120.0;
  // The point looked at is at least this far away (horizontally) while the trajectory goes on
  // that far, so that a vehicle creeping slowly still faces where it goes.
  double min_lookahead_m = 0.2;
};

// Angle wrapped into [-pi, pi].
double wrapAngle(double a);

// The yaw after dt: from `yaw` one lag step (and at most max_rate_dps * dt) towards `target`.
double turnTowards(double yaw, double target, double dt, const HeadingParams& params);

// The yaw after dt on `trajectory` at its time t, the vehicle at `position`: towards the
// trajectory's point lookahead_s ahead, or the first later one min_lookahead_m away horizontally
// (its end at most). Unchanged while that point is within 5 cm horizontally (hovering, or nearly
// there).
double followHeading(double yaw, const Trajectory& trajectory, double t,
                     const Eigen::Vector3d& position, double dt, const HeadingParams& params);

}  // namespace mmh
