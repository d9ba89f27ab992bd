// Braking trajectory: from a moving state to rest along the direction of motion with
// |acceleration| <= a_max (checked exactly). What the arbiter commits when no mode gave a usable
// answer and danger is ahead, or when its inputs go stale.
#pragma once

#include "mmh/common/trajectory.hpp"

namespace mmh::arbiter {

Trajectory makeStoppingTrajectory(const KinematicState& start, double max_acc_mps2,
                                  double max_vel_mps);

}  // namespace mmh::arbiter
