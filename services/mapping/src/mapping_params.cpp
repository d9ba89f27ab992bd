#include "mmh/mapping/mapping_params.hpp"

#include "mmh/common/config_constraints.hpp"

namespace mmh::mapping {

MappingParams loadMappingParams(const Config& c) {
  MappingParams p;
  p.resolution_m = c.getDouble("map.resolution_m");
  p.window_size_m = c.getVector3("map.window_size_m");
  p.keyframe_period_s = c.getDouble("mapping.keyframe_period_s");
  p.delta_repeat = c.getInt("mapping.delta_repeat");
  p.window_recenter_m = c.getDouble("mapping.window_recenter_m");
  p.max_range_m = c.getDouble("mapping.max_range_m");
  p.max_points = c.getInt("mapping.max_points");
  p.prob_hit = c.getDouble("mapping.prob_hit");
  p.prob_miss = c.getDouble("mapping.prob_miss");
  p.clamp_min = c.getDouble("mapping.clamp_min");
  p.clamp_max = c.getDouble("mapping.clamp_max");
  p.occupancy_threshold = c.getDouble("mapping.occupancy_threshold");
  checkConfigConstraints(c);  // among them: clamp_min <= occupancy_threshold <= clamp_max
  const Eigen::Vector3i cells = p.windowCells();
  if (static_cast<int64_t>(cells.x()) * cells.y() * cells.z() > int64_t{512} * 512 * 64) {
    throw ConfigError(c.source() +
                      ": key 'map.window_size_m' / 'map.resolution_m' give a window "
                      "of more than 512 x 512 x 64 cells (the LOCAL_MAP limit)");
  }
  return p;
}

}  // namespace mmh::mapping
