// Parameters of the awareness service, read from the deployment configuration with range checks
// (a bad value stops the service at start-up with the key named).
#pragma once

#include "mmh/common/awareness.hpp"
#include "mmh/common/config.hpp"

namespace mmh::awareness {

struct Params {
  AwarenessParams algorithm;  // awareness.sensor_range_m, awareness.narrow_probe_dist_m
  double inflation_m = 0.3;   // map.inflation_m: obstacles grow by this for JudgePointSafe
};

// Reads awareness.sensor_range_m, awareness.narrow_probe_dist_m and map.inflation_m (ranges and
// defaults: mmh/common/config_registry.hpp). Throws ConfigError.
Params loadParams(const Config& config);

}  // namespace mmh::awareness
