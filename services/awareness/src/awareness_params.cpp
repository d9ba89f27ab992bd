#include "mmh/awareness/awareness_params.hpp"

#include "mmh/common/config_constraints.hpp"

namespace mmh::awareness {

Params loadParams(const Config& config) {
  Params p;
  p.algorithm.sensor_range_m = config.getDouble("awareness.sensor_range_m");
  p.algorithm.narrow_probe_dist_m = config.getDouble("awareness.narrow_probe_dist_m");
  p.inflation_m = config.getDouble("map.inflation_m");
  checkConfigConstraints(config);
  return p;
}

}  // namespace mmh::awareness
