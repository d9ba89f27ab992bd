#include "mmh/awareness/awareness_params.hpp"

namespace mmh::awareness {

Params loadParams(const Config& config) {
  Params p;
  p.algorithm.sensor_range_m = config.getDouble("awareness.sensor_range_m", 0.1, 100.0);
  p.algorithm.narrow_probe_dist_m = config.getDouble("awareness.narrow_probe_dist_m", 0.05, 10.0);
  p.inflation_m = config.getDouble("map.inflation_m", 0.0, 5.0);
  return p;
}

}  // namespace mmh::awareness
