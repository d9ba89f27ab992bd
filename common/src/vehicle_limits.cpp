#include "mmh/common/vehicle_limits.hpp"

namespace mmh {

VehicleLimits loadVehicleLimits(const Config& config) {
  VehicleLimits v;
  v.max_vel_mps = config.getDouble("vehicle.max_vel_mps");
  v.max_acc_mps2 = config.getDouble("vehicle.max_acc_mps2");
  return v;
}

}  // namespace mmh
