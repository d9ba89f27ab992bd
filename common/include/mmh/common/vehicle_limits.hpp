// The vehicle's dynamic limits (vehicle.max_vel_mps, vehicle.max_acc_mps2), shared by every
// service: one loader, so that every service reads them with the same ranges.
#pragma once

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

}  // namespace mmh
