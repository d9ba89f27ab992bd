#include "mmh/mapping/mapper.hpp"

#include <cmath>

namespace mmh::mapping {

namespace {

void fillGeometry(const OccupancyMap& map, int64_t map_seq, local_map_t& msg) {
  msg.map_seq = map_seq;
  msg.resolution_m = map.resolution();
  for (int i = 0; i < 3; ++i) {
    msg.origin_index[i] = map.windowOrigin()[i];
    msg.size[i] = map.windowSize()[i];
  }
}

// The same messages as common's makeKeyframe / makeDelta, from the map's state array (the map
// keeps no VoxelGrid: moving one costs a full copy of the window).
local_map_t keyframeOf(const OccupancyMap& map, int64_t map_seq) {
  local_map_t msg{};
  fillGeometry(map, map_seq, msg);
  msg.kind = local_map_t::KIND_KEYFRAME;
  msg.base_seq = 0;
  std::vector<CellChange> known;
  const std::vector<uint8_t>& states = map.windowStates();
  for (size_t i = 0; i < states.size(); ++i) {
    if (states[i] != 0)
      known.emplace_back(static_cast<int64_t>(i), static_cast<Occupancy>(states[i]));
  }
  msg.runs = encodeRuns(known);
  msg.num_bytes = static_cast<int32_t>(msg.runs.size());
  msg.num_changed = static_cast<int32_t>(known.size());
  return msg;
}

local_map_t deltaOf(const OccupancyMap& map, int64_t map_seq,
                    const std::vector<CellChange>& changes) {
  local_map_t msg{};
  fillGeometry(map, map_seq, msg);
  msg.kind = local_map_t::KIND_DELTA;
  msg.base_seq = map_seq - 1;
  msg.runs = encodeRuns(changes);
  msg.num_bytes = static_cast<int32_t>(msg.runs.size());
  msg.num_changed = static_cast<int32_t>(changes.size());
  return msg;
}

}  // namespace

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
    result.map = keyframeOf(map_, map_seq_);
    last_keyframe_utime_ = utime;
    keyframe_requested_ = false;
    // Once per keyframe: bring the tree up to date and free the memory the window left behind.
    map_.flush();
    map_.pruneOutsideWindow();
  } else {
    result.map = deltaOf(map_, map_seq_, map_.takeChanges());
  }
  result.map.header.utime = utime;
  return result;
}

}  // namespace mmh::mapping
