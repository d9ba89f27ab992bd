// Parameters of the trajectory server (section `setpoint`, plus the vehicle limits it brakes
// within), read and range-checked at start-up so that a bad file names the key.
#pragma once

#include "mmh/common/config.hpp"
#include "mmh/common/heading.hpp"

namespace mmh::setpoint {

struct Params {
  double rate_hz = 100.0;     // setpoint.rate_hz
  double watchdog_s = 2.5;    // setpoint.watchdog_s: silence of TRAJECTORY and arbiter HEARTBEAT
  double max_vel_mps = 3.0;   // vehicle.max_vel_mps
  double max_acc_mps2 = 2.0;  // vehicle.max_acc_mps2: the watchdog's braking stays within it
  // setpoint.yaw_lookahead_s, setpoint.yaw_lookahead_min_m, setpoint.max_yaw_rate_dps; no lag
  // of its own (the flight controller's yaw loop has one).
  HeadingParams heading{0.5, 0.0, 90.0};
};

// Throws ConfigError naming the key.
Params loadParams(const Config& config);

}  // namespace mmh::setpoint
