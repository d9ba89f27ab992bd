// The vehicle's dynamic limits (vehicle.max_vel_mps, vehicle.max_acc_mps2), shared by every
// service: one loader, so that every service reads them with the same ranges.
#pragma once

#include <algorithm>
#include <cmath>

#include "mmh/common/config.hpp"

namespace mmh {

struct VehicleLimits {
  double max_vel_mps = 3.0;
  double max_acc_mps2 = 2.0;
};

// Throws ConfigError naming the key.
VehicleLimits loadVehicleLimits(const Config& config);

// Minimum time to travel `length_m` along a path from rest to rest with |v| <= max_vel_mps and
// |a| <= max_acc_mps2: L / v + v / a when v_max is reached, 2 sqrt(L / a) otherwise. 39.9 m at
// 3 m/s and 2 m/s^2 gives 14.8 s (docs/benchmark.md). A negative length gives a negative time.
double restToRestTime(double length_m, double max_vel_mps, double max_acc_mps2);

// Distance to brake from speed_mps to rest at max_acc_mps2: v^2 / (2 a).
inline double stoppingDistance(double speed_mps, double max_acc_mps2) {
  return speed_mps * speed_mps / (2.0 * max_acc_mps2);
}

// The speed a planner keeps to for a request that asks for requested_mps: that speed when it is
// positive and below the vehicle's limit, else the vehicle's limit (plan_request_t.max_speed_mps).
inline double speedLimitFor(double requested_mps, double vehicle_max_mps) {
  return requested_mps > 0.0 ? std::min(requested_mps, vehicle_max_mps) : vehicle_max_mps;
}

// The highest speed v from which the vehicle, flying on for reaction_s and then braking at
// max_acc_mps2, comes to rest within distance_m: the positive root of v^2 / (2 a) + v t = d.
inline double speedStoppingWithin(double distance_m, double reaction_s, double max_acc_mps2) {
  if (distance_m <= 0.0) return 0.0;
  const double a = max_acc_mps2, t = reaction_s;
  return a * (std::sqrt(t * t + 2.0 * distance_m / a) - t);
}

}  // namespace mmh
