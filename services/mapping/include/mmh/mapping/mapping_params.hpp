// Parameters of the mapping service (section `mapping` of the configuration and the shared map
// keys), read and range-checked at start-up.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "mmh/common/config.hpp"

namespace mmh::mapping {

struct MappingParams {
  double resolution_m = 0.1;                                         // map.resolution_m
  Eigen::Vector3d window_size_m = Eigen::Vector3d(32.0, 32.0, 4.0);  // map.window_size_m
  double keyframe_period_s = 1.0;  // a whole-window LOCAL_MAP at least this often
  int delta_repeat = 5;            // a delta holds the cells of this many deltas (>= 1)
  double window_recenter_m = 1.0;  // move the window when the vehicle is this far off its centre
  double max_range_m = 10.0;       // returns beyond this count as free space up to it (crop)
  int64_t max_points = 500000;     // larger scans are rejected
  // OctoMap's usual sensor model: log-odds update per hit / miss, clamped.
  double prob_hit = 0.7;
  double prob_miss = 0.4;
  double clamp_min = 0.12;
  double clamp_max = 0.97;
  double occupancy_threshold = 0.5;  // occupied above this probability

  Eigen::Vector3i windowCells() const {
    return (window_size_m / resolution_m).array().round().cast<int>().max(1).matrix();
  }
};

// Throws ConfigError naming the key when one is missing or out of range.
MappingParams loadMappingParams(const Config& config);

}  // namespace mmh::mapping
