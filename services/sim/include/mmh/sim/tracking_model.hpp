// What a flight controller makes of a setpoint stream, in its simplest honest form: a
// second-order position/velocity loop with acceleration feed-forward, a bandwidth and an
// acceleration limit (sim.tracking.*). mmh-sim --follow setpoint flies SETPOINT through it, so
// the chain a real vehicle uses (arbiter -> mmh-setpoint -> controller) is exercised and its
// tracking error measured.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "mmh/common/trajectory.hpp"

namespace mmh::sim {

struct TrackingParams {
  double bandwidth_hz = 1.0;   // natural frequency of the position loop
  double damping_ratio = 1.0;  // 1: critically damped
  double max_acc_mps2 = 4.0;   // the airframe's acceleration limit
  // Setpoints are carried forward along their own derivatives for at most this long; past it
  // (the stream stopped) the controller holds the point reached, at rest.
  double setpoint_timeout_s = 0.1;
};

// One setpoint as the controller received it.
struct SetpointSample {
  int64_t utime = 0;
  int64_t trajectory_id = 0;
  bool on_trajectory = false;  // tracking a committed trajectory (not holding or braking)
  KinematicState state;
  Eigen::Vector3d jerk = Eigen::Vector3d::Zero();
  double yaw_rad = 0.0;
};

// The reference at `utime`: the setpoint carried forward by its velocity, acceleration and jerk
// (at most setpoint_timeout_s; beyond, that point at rest).
KinematicState referenceAt(const SetpointSample& setpoint, int64_t utime,
                           const TrackingParams& params);

// One step of dt: a = a_ref + w^2 (p_ref - p) + 2 zeta w (v_ref - v), |a| <= max_acc_mps2 (w =
// 2 pi bandwidth_hz), integrated exactly for a constant acceleration over the step.
KinematicState trackingStep(const KinematicState& vehicle, const KinematicState& reference,
                            double dt, const TrackingParams& params);

}  // namespace mmh::sim
