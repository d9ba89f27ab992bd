// The mapping pipeline without LCM: scan -> filter (scan_filter.hpp) -> window placement and
// insertion into the OccupancyMap -> the LOCAL_MAP message, a keyframe (whole window) at least
// every keyframe_period_s and a delta otherwise: the cells changed since the previous message,
// and those of the delta_repeat - 1 deltas before it, so that a lost message costs nothing.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "mmh/local_map_t.hpp"
#include "mmh/mapping/mapping_params.hpp"
#include "mmh/mapping/occupancy_map.hpp"
#include "mmh/mapping/scan_filter.hpp"

namespace mmh::mapping {

class Mapper {
 public:
  explicit Mapper(const MappingParams& params);

  struct Result {
    ScanError error = ScanError::kNone;  // kNone: the scan was inserted and `map` is valid
    std::string reason;
    FilterStats filter;
    InsertStats insert;
    local_map_t map;  // header.utime = the scan's time; source and seq are the publisher's
    bool keyframe = false;
    bool window_moved = false;
  };

  // The vehicle position the window follows (from ODOMETRY). Without it the scan's sensor
  // position is used.
  void setVehiclePosition(const Eigen::Vector3d& position);

  // Inserts a scan taken at `utime` (message clock) and makes the next LOCAL_MAP message.
  Result processScan(const ScanInput& scan, int64_t utime);

  // The next message will be a keyframe (e.g. a receiver asked to resynchronise).
  void requestKeyframe() { keyframe_requested_ = true; }

  const OccupancyMap& map() const { return map_; }
  const MappingParams& params() const { return params_; }
  int64_t mapSeq() const { return map_seq_; }

 private:
  MappingParams params_;
  OccupancyMap map_;
  FilteredScan filtered_;
  Eigen::Vector3d vehicle_ = Eigen::Vector3d::Zero();
  bool have_vehicle_ = false;
  local_map_t nextDelta();

  int64_t map_seq_ = 0;
  int64_t last_keyframe_seq_ = 0;
  int64_t last_keyframe_utime_ = 0;
  std::deque<std::vector<int64_t>> recent_changes_;  // changed cells of the last deltas
  bool keyframe_requested_ = true;
};

}  // namespace mmh::mapping
