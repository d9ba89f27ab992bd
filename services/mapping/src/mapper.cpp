#include "mmh/mapping/mapper.hpp"

#include <algorithm>
#include <cmath>

namespace mmh::mapping {

namespace {

MapUpdate geometryOf(const OccupancyMap& map, int64_t map_seq) {
  MapUpdate u;
  u.map_seq = map_seq;
  u.resolution_m = map.resolution();
  u.origin_index = map.windowOrigin();
  u.size = map.windowSize();
  return u;
}

// The same content as common's makeKeyframe / makeDelta, from the map's state array (the map
// keeps no VoxelGrid: moving one costs a full copy of the window).
MapUpdate keyframeOf(const OccupancyMap& map, int64_t map_seq) {
  MapUpdate u = geometryOf(map, map_seq);
  u.keyframe = true;
  u.base_seq = 0;
  const std::vector<uint8_t>& states = map.windowStates();
  for (size_t i = 0; i < states.size(); ++i) {
    if (states[i] != 0)
      u.cells.emplace_back(static_cast<int64_t>(i), static_cast<Occupancy>(states[i]));
  }
  return u;
}

MapUpdate deltaOf(const OccupancyMap& map, int64_t map_seq, int64_t base_seq,
                  std::vector<CellChange> changes) {
  MapUpdate u = geometryOf(map, map_seq);
  u.keyframe = false;
  u.base_seq = base_seq;
  u.cells = std::move(changes);
  return u;
}

}  // namespace

Mapper::Mapper(const MappingParams& params) : params_(params), map_(params) {}

void Mapper::setVehiclePosition(const Eigen::Vector3d& position) {
  if (!position.allFinite()) return;
  vehicle_ = position;
  have_vehicle_ = true;
}

void Mapper::maintain() {
  if (!maintenance_due_) return;
  // Once per keyframe: bring the tree up to date and free the memory the window left behind.
  map_.flush();
  map_.pruneOutsideWindow();
  maintenance_due_ = false;
}

Mapper::Result Mapper::processScan(const ScanInput& scan, int64_t utime) {
  maintain();
  Result result;
  result.error = filterScan(scan, params_, &filtered_, &result.filter, &result.reason);
  if (result.error != ScanError::kNone) return result;
  result.window_moved = map_.followVehicle(have_vehicle_ ? vehicle_ : scan.sensor_position);
  result.insert = map_.insert(filtered_);
  const int64_t period_us = std::llround(params_.keyframe_period_s * 1e6);
  const bool keyframe = keyframe_requested_ || utime - last_keyframe_utime_ >= period_us ||
                        utime < last_keyframe_utime_;
  ++map_seq_;
  if (keyframe && map_seq_ == 1) {
    // Nothing sent before: receivers need the whole window first.
    result.map = keyframeOf(map_, map_seq_);
  } else {
    result.map = nextDelta();
    result.keyframe_follows = keyframe;
  }
  if (keyframe) {
    map_.clearChanges();
    recent_changes_.clear();
    last_keyframe_seq_ = map_seq_;
    last_keyframe_utime_ = utime;
    keyframe_requested_ = false;
    maintenance_due_ = true;
  }
  result.map.utime = utime;
  return result;
}

MapUpdate Mapper::keyframe() const {
  MapUpdate u = keyframeOf(map_, map_seq_);
  u.utime = last_keyframe_utime_;  // the scan that called for it
  return u;
}

MapUpdate Mapper::nextDelta() {
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
