#include "mmh/common/vehicle_limits.hpp"

#include <cmath>

namespace mmh {

VehicleLimits loadVehicleLimits(const Config& config) {
  VehicleLimits v;
  v.max_vel_mps = config.getDouble("vehicle.max_vel_mps");
  v.max_acc_mps2 = config.getDouble("vehicle.max_acc_mps2");
  return v;
}

double restToRestTime(double length_m, double max_vel_mps, double max_acc_mps2) {
  if (length_m < 0.0) return -1.0;
  if (length_m >= max_vel_mps * max_vel_mps / max_acc_mps2)
    return length_m / max_vel_mps + max_vel_mps / max_acc_mps2;
  return 2.0 * std::sqrt(length_m / max_acc_mps2);
}

}  // namespace mmh
