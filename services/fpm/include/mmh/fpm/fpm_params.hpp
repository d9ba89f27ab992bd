// Parameters of the Fast Planning Mode, read from the deployment configuration with range checks
// (a bad value stops the service at start-up with the key named).
#pragma once

#include <Eigen/Core>

#include "mmh/common/config.hpp"

namespace mmh::fpm {

struct Params {
  double max_vel_mps = 3.0;     // vehicle.max_vel_mps: |v| <= this over the whole trajectory
  double max_acc_mps2 = 2.0;    // vehicle.max_acc_mps2: |a| <= this over the whole trajectory
  double time_weight = 1000.0;  // fpm.time_weight: rho in J = int |jerk|^2 dt + rho T
  Eigen::Vector3d geofence_min_m = Eigen::Vector3d::Constant(-1e9);  // geofence.min_m
  Eigen::Vector3d geofence_max_m = Eigen::Vector3d::Constant(1e9);   // geofence.max_m
  // Optimiser tuning (fpm.*).
  double penalty_weight = 1e6;        // weight of the quadratic limit-violation penalties
  double limit_margin_ratio = 0.005;  // guess and penalties use (1 - margin) x the limits
  int samples_per_piece = 8;          // penalty samples per polynomial piece
  int max_evaluations = 12;           // cost evaluations per optimisation run
};

// Reads vehicle.max_vel_mps, vehicle.max_acc_mps2, geofence.min_m / max_m and the fpm section.
// Throws ConfigError naming the key.
Params loadParams(const Config& config);

}  // namespace mmh::fpm
