#include "mmh/mapping/mapping_params.hpp"

namespace mmh::mapping {

MappingParams loadMappingParams(const Config& c) {
  MappingParams p;
  p.resolution_m = c.getDouble("map.resolution_m", 0.02, 1.0);
  p.window_size_m = c.getVector3("map.window_size_m", 1.0, 200.0);
  p.keyframe_period_s = c.getDouble("mapping.keyframe_period_s", 0.05, 60.0);
  p.delta_repeat = c.getInt("mapping.delta_repeat", 1, 16);
  p.window_recenter_m = c.getDouble("mapping.window_recenter_m", 0.0, 50.0);
  p.max_range_m = c.getDouble("mapping.max_range_m", 0.1, 100.0);
  p.max_points = c.getInt("mapping.max_points", 1, 4'000'000);
  p.prob_hit = c.getDouble("mapping.prob_hit", 0.5001, 0.999);
  p.prob_miss = c.getDouble("mapping.prob_miss", 0.001, 0.4999);
  p.clamp_min = c.getDouble("mapping.clamp_min", 0.001, 0.4999);
  p.clamp_max = c.getDouble("mapping.clamp_max", 0.5001, 0.999);
  p.occupancy_threshold = c.getDouble("mapping.occupancy_threshold", p.clamp_min, p.clamp_max);
  const Eigen::Vector3i cells = p.windowCells();
  if (static_cast<int64_t>(cells.x()) * cells.y() * cells.z() > int64_t{512} * 512 * 64) {
    throw ConfigError(c.source() +
                      ": key 'map.window_size_m' / 'map.resolution_m' give a window "
                      "of more than 512 x 512 x 64 cells (the LOCAL_MAP limit)");
  }
  return p;
}

}  // namespace mmh::mapping
