#include "mmh/mapping/mapper.hpp"

#include <cmath>

namespace mmh::mapping {

Mapper::Mapper(const MappingParams& params) : params_(params), map_(params) {}

void Mapper::setVehiclePosition(const Eigen::Vector3d& position) {
  if (!position.allFinite()) return;
  vehicle_ = position;
  have_vehicle_ = true;
}

Mapper::Result Mapper::processScan(const ScanInput& scan, int64_t utime) {
  Result result;
  result.error = filterScan(scan, params_, &filtered_, &result.filter, &result.reason);
  if (result.error != ScanError::kNone) return result;
  result.window_moved = map_.followVehicle(have_vehicle_ ? vehicle_ : scan.sensor_position);
  result.insert = map_.insert(filtered_);
  const int64_t period_us = std::llround(params_.keyframe_period_s * 1e6);
  result.keyframe = keyframe_requested_ || utime - last_keyframe_utime_ >= period_us ||
                    utime < last_keyframe_utime_;
  ++map_seq_;
  if (result.keyframe) {
    map_.clearChanges();
    result.map = makeKeyframe(map_.window(), map_seq_);
    last_keyframe_utime_ = utime;
    keyframe_requested_ = false;
    // Once per keyframe: free the tree memory the window left behind.
    map_.pruneOutsideWindow();
  } else {
    result.map = makeDelta(map_.window(), map_seq_, map_.takeChanges());
  }
  result.map.header.utime = utime;
  return result;
}

}  // namespace mmh::mapping
