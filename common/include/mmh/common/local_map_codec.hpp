// LOCAL_MAP encoding (sparse run-length code of voxel states, see lcmtypes/local_map_t.lcm) and
// the receiver every map consumer uses: applies keyframes and deltas, notices gaps.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "mmh/common/voxel_grid.hpp"
#include "mmh/local_map_t.hpp"

namespace mmh {

// One changed cell of a window: linear index (x fastest) and its new state.
using CellChange = std::pair<int64_t, Occupancy>;

// Encodes changes sorted by index into (skip, length, state) runs.
std::vector<uint8_t> encodeRuns(const std::vector<CellChange>& sorted_changes);

// Keyframe of the whole window (every known cell).
local_map_t makeKeyframe(const VoxelGrid& grid, int64_t map_seq);

// Delta from base_seq (default map_seq - 1) to map_seq: move the window to grid's origin, then
// apply `changes` (indices in the new window, sorted): every cell that changed since base_seq.
local_map_t makeDelta(const VoxelGrid& grid, int64_t map_seq,
                      const std::vector<CellChange>& sorted_changes, int64_t base_seq = -1);

// Decodes a message's runs into `grid` (whose geometry must already match); false with a reason
// if the runs are malformed or leave the window. Cells written are appended to `written` if given.
bool applyRuns(const local_map_t& msg, VoxelGrid& grid, std::string* error,
               std::vector<int64_t>* written = nullptr);

// Checks of a decoded LOCAL_MAP that do not need the receiver's state.
bool validateLocalMap(const local_map_t& msg, std::string* error);

// Rebuilds the sender's window from a stream of LOCAL_MAP messages.
class LocalMapReceiver {
 public:
  enum class Result {
    kApplied,             // the grid now equals the sender's window at msg.map_seq
    kWaitingForKeyframe,  // a delta arrived before any keyframe or after a gap: ignored
    kGap,                 // a delta's base_seq is newer than the last applied map: waiting now
    kStale,               // older than or equal to what is applied: ignored
    kAlreadyBuilt,        // the keyframe of the map its delta already built: ignored
    kRejected,            // malformed message: ignored, state unchanged
  };

  explicit LocalMapReceiver(double inflation_radius_m = 0.0)
      : inflation_radius_(inflation_radius_m) {}

  Result apply(const local_map_t& msg, std::string* reason = nullptr);

  bool hasMap() const { return synced_; }
  const VoxelGrid& grid() const { return grid_; }
  int64_t mapSeq() const { return last_seq_; }
  int64_t mapUtime() const { return last_utime_; }
  int64_t gapsDetected() const { return gaps_; }
  // Deltas applied exactly although messages before them were lost (within the sender's repeat).
  int64_t lossesBridged() const { return bridged_; }
  // Cells changed by the last applied message (empty after a keyframe: everything changed).
  const std::vector<int64_t>& lastChangedCells() const { return last_changed_; }
  bool lastWasKeyframe() const { return last_was_keyframe_; }

 private:
  double inflation_radius_;
  VoxelGrid grid_;
  bool synced_ = false;
  bool have_grid_ = false;
  int64_t last_seq_ = 0;
  int64_t last_utime_ = 0;
  int64_t gaps_ = 0;
  int64_t bridged_ = 0;
  std::vector<int64_t> last_changed_;
  std::vector<uint8_t> keyframe_cells_;  // a keyframe's cells, decoded before they are applied
  bool last_was_keyframe_ = false;
};

}  // namespace mmh
