#include "mmh/setpoint/setpoint_params.hpp"

#include "mmh/common/config_constraints.hpp"
#include "mmh/common/vehicle_limits.hpp"

namespace mmh::setpoint {

Params loadParams(const Config& c) {
  Params p;
  p.rate_hz = c.getDouble("setpoint.rate_hz");
  p.watchdog_s = c.getDouble("setpoint.watchdog_s");
  const VehicleLimits vehicle = loadVehicleLimits(c);
  p.max_vel_mps = vehicle.max_vel_mps;
  p.max_acc_mps2 = vehicle.max_acc_mps2;
  p.heading.lookahead_s = c.getDouble("setpoint.yaw_lookahead_s");
  p.heading.min_lookahead_m = c.getDouble("setpoint.yaw_lookahead_min_m");
  p.heading.time_constant_s = 0.0;
  p.heading.max_rate_dps = c.getDouble("setpoint.max_yaw_rate_dps");
  checkConfigConstraints(c);
  return p;
}

}  // namespace mmh::setpoint
