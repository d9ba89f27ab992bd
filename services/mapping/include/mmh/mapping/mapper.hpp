// The mapping pipeline without LCM: scan -> filter (scan_filter.hpp) -> window placement and
// insertion into the OccupancyMap -> the content of the LOCAL_MAP messages (MapUpdate; the node
// encodes them, mapping_node.hpp toLocalMap). Every scan gives a delta: the cells changed since
// the previous message, and those of the delta_repeat - 1 deltas before it, so that a lost
// message costs nothing. The first scan gives a keyframe (whole window) instead, and at least
// every keyframe_period_s a keyframe of the same map follows the delta, for receivers that lost
// more: the delta goes first because a whole window takes tens of ms to build, send and apply,
// and a newly mapped obstacle must not wait for it.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "mmh/common/local_map_codec.hpp"
#include "mmh/mapping/mapping_params.hpp"
#include "mmh/mapping/occupancy_map.hpp"
#include "mmh/mapping/scan_filter.hpp"

namespace mmh::mapping {

// One LOCAL_MAP's content without the wire type.
struct MapUpdate {
  bool keyframe = false;
  int64_t map_seq = 0;
  int64_t base_seq = 0;  // keyframe: 0; delta: the map it applies to
  int64_t utime = 0;     // the scan's time
  double resolution_m = 0.0;
  Eigen::Vector3i origin_index = Eigen::Vector3i::Zero();  // window cell (0, 0, 0)
  Eigen::Vector3i size = Eigen::Vector3i::Zero();          // window size in voxels
  // Sorted by linear index: keyframe, every known cell; delta, the changed cells (current state).
  std::vector<CellChange> cells;
};

class Mapper {
 public:
  explicit Mapper(const MappingParams& params);

  struct Result {
    ScanError error = ScanError::kNone;  // kNone: the scan was inserted and `map` is valid
    std::string reason;
    FilterStats filter;
    InsertStats insert;
    MapUpdate map;                  // the message to send now
    bool keyframe_follows = false;  // then send keyframe(): the same map_seq as the whole window
    bool window_moved = false;
  };

  // The vehicle position the window follows (from ODOMETRY). Without it the scan's sensor
  // position is used.
  void setVehiclePosition(const Eigen::Vector3d& position);

  // Inserts a scan taken at `utime` (message clock) and makes the next LOCAL_MAP message.
  Result processScan(const ScanInput& scan, int64_t utime);

  // The whole window at the last scan (map_seq and utime of its delta), when processScan said
  // keyframe_follows; call it after sending that delta and before the next scan.
  MapUpdate keyframe() const;

  // The upkeep a keyframe calls for (writing the window back to the tree, freeing what the window
  // left behind), which changes no message: called after the keyframe is sent, so that receivers
  // do not wait for it (else the next processScan does it first).
  void maintain();

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
  MapUpdate nextDelta();

  int64_t map_seq_ = 0;
  int64_t last_keyframe_seq_ = 0;
  int64_t last_keyframe_utime_ = 0;
  std::deque<std::vector<int64_t>> recent_changes_;  // changed cells of the last deltas
  bool keyframe_requested_ = true;
  bool maintenance_due_ = false;
};

}  // namespace mmh::mapping
