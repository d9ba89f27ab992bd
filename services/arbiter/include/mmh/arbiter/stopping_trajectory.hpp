// Braking trajectory: from a moving state to rest along the direction of motion with
// |acceleration| <= a_max (checked exactly). What the arbiter commits when no mode gave a usable
// answer and danger is ahead, or when its inputs go stale.
#pragma once

#include "mmh/common/trajectory.hpp"

namespace mmh::arbiter {

Trajectory makeStoppingTrajectory(const KinematicState& start, double max_acc_mps2,
                                  double max_vel_mps);

// Brakes along the path of `path` from its time t0: the same curve, re-timed with a smoothly
// decreasing speed (so an avoidance manoeuvre under way is kept), fitted with minimum-jerk pieces
// through points of the re-timed curve. Starts exactly in path's state at t0 and ends at rest;
// |a| <= a_max checked exactly.
Trajectory makeStoppingTrajectory(const Trajectory& path, double t0, double max_acc_mps2,
                                  double max_vel_mps);

}  // namespace mmh::arbiter
