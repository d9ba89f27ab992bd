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

}  // namespace mmh
