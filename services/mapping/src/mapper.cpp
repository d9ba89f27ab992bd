#include "mmh/mapping/mapper.hpp"

#include <algorithm>
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

local_map_t deltaOf(const OccupancyMap& map, int64_t map_seq, int64_t base_seq,
                    const std::vector<CellChange>& changes) {
  local_map_t msg{};
  fillGeometry(map, map_seq, msg);
  msg.kind = local_map_t::KIND_DELTA;
  msg.base_seq = base_seq;
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
    recent_changes_.clear();
    result.map = keyframeOf(map_, map_seq_);
    last_keyframe_seq_ = map_seq_;
    last_keyframe_utime_ = utime;
    keyframe_requested_ = false;
    // Once per keyframe: bring the tree up to date and free the memory the window left behind.
    map_.flush();
    map_.pruneOutsideWindow();
  } else {
    result.map = nextDelta();
  }
  result.map.header.utime = utime;
  return result;
}

local_map_t Mapper::nextDelta() {
  // This delta's cells and those of the deltas before it, up to delta_repeat in all and never
  // past the last keyframe, each with its current state: a receiver that lost fewer messages in
  // a row applies it exactly.
  recent_changes_.push_back(map_.takeChangedCells());
  while (static_cast<int>(recent_changes_.size()) > params_.delta_repeat) {
    recent_changes_.pop_front();
  }
  const int64_t base_seq =
      std::max(last_keyframe_seq_, map_seq_ - static_cast<int64_t>(recent_changes_.size()));
  std::vector<int64_t> cells;
  for (const auto& changed : recent_changes_)
    cells.insert(cells.end(), changed.begin(), changed.end());
  return deltaOf(map_, map_seq_, base_seq, map_.windowChangesOf(cells));
}

}  // namespace mmh::mapping
