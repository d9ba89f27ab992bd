#include "mmh/common/local_map_codec.hpp"

#include <algorithm>
#include <cmath>

namespace mmh {
namespace {

// Largest window a receiver accepts (cells); 512 x 512 x 64 at most, about 16 M cells.
constexpr int64_t kMaxWindowCells = int64_t{512} * 512 * 64;
constexpr int kMaxWindowEdge = 4096;

void putVarint(std::vector<uint8_t>& out, uint64_t v) {
  while (v >= 0x80) {
    out.push_back(static_cast<uint8_t>(v | 0x80));
    v >>= 7;
  }
  out.push_back(static_cast<uint8_t>(v));
}

bool getVarint(const std::vector<uint8_t>& in, size_t& pos, uint64_t& v) {
  v = 0;
  for (int shift = 0; shift < 64; shift += 7) {
    if (pos >= in.size()) return false;
    uint8_t b = in[pos++];
    v |= static_cast<uint64_t>(b & 0x7f) << shift;
    if (!(b & 0x80)) return true;
  }
  return false;
}

void fillGeometry(const VoxelGrid& grid, int64_t map_seq, local_map_t& msg) {
  msg.map_seq = map_seq;
  msg.resolution_m = grid.resolution();
  for (int i = 0; i < 3; ++i) {
    msg.origin_index[i] = grid.originIndex()[i];
    msg.size[i] = grid.size()[i];
  }
}

}  // namespace

std::vector<uint8_t> encodeRuns(const std::vector<CellChange>& changes) {
  std::vector<uint8_t> out;
  int64_t cursor = 0;  // first cell after the previous run
  size_t i = 0;
  while (i < changes.size()) {
    const int64_t start = changes[i].first;
    const Occupancy state = changes[i].second;
    size_t j = i + 1;
    while (j < changes.size() && changes[j].first == changes[j - 1].first + 1 &&
           changes[j].second == state) {
      ++j;
    }
    putVarint(out, static_cast<uint64_t>(start - cursor));
    putVarint(out, static_cast<uint64_t>(j - i));
    out.push_back(static_cast<uint8_t>(state));
    cursor = start + static_cast<int64_t>(j - i);
    i = j;
  }
  return out;
}

local_map_t makeKeyframe(const VoxelGrid& grid, int64_t map_seq) {
  local_map_t msg{};
  fillGeometry(grid, map_seq, msg);
  msg.kind = local_map_t::KIND_KEYFRAME;
  msg.base_seq = 0;
  std::vector<CellChange> known;
  const auto& cells = grid.rawCells();
  for (int64_t i = 0; i < grid.numCells(); ++i) {
    if (cells[i] != static_cast<uint8_t>(Occupancy::kUnknown)) {
      known.emplace_back(i, static_cast<Occupancy>(cells[i]));
    }
  }
  msg.runs = encodeRuns(known);
  msg.num_bytes = static_cast<int32_t>(msg.runs.size());
  msg.num_changed = static_cast<int32_t>(known.size());
  return msg;
}

local_map_t makeDelta(const VoxelGrid& grid, int64_t map_seq,
                      const std::vector<CellChange>& sorted_changes, int64_t base_seq) {
  local_map_t msg{};
  fillGeometry(grid, map_seq, msg);
  msg.kind = local_map_t::KIND_DELTA;
  msg.base_seq = base_seq < 0 ? map_seq - 1 : base_seq;
  msg.runs = encodeRuns(sorted_changes);
  msg.num_bytes = static_cast<int32_t>(msg.runs.size());
  msg.num_changed = static_cast<int32_t>(sorted_changes.size());
  return msg;
}

bool validateLocalMap(const local_map_t& msg, std::string* error) {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (msg.kind != local_map_t::KIND_KEYFRAME && msg.kind != local_map_t::KIND_DELTA)
    return fail("unknown kind " + std::to_string(msg.kind));
  if (!std::isfinite(msg.resolution_m) || msg.resolution_m < 0.01 || msg.resolution_m > 10.0)
    return fail("resolution_m outside [0.01, 10]");
  int64_t cells = 1;
  for (int i = 0; i < 3; ++i) {
    if (msg.size[i] <= 0 || msg.size[i] > kMaxWindowEdge)
      return fail("window size outside [1, " + std::to_string(kMaxWindowEdge) + "]");
    if (std::abs(static_cast<int64_t>(msg.origin_index[i])) > (int64_t{1} << 28))
      return fail("origin_index out of range");
    cells *= msg.size[i];
  }
  if (cells > kMaxWindowCells) return fail("window has too many cells");
  if (msg.num_bytes < 0 || static_cast<size_t>(msg.num_bytes) != msg.runs.size())
    return fail("num_bytes disagrees with the data");
  if (msg.map_seq <= 0) return fail("map_seq must be positive");
  if (msg.kind == local_map_t::KIND_DELTA && (msg.base_seq < 0 || msg.base_seq >= msg.map_seq))
    return fail("delta base_seq must be in [0, map_seq - 1]");
  return true;
}

namespace {

struct Run {
  int64_t start, length;
  uint8_t state;
};

// The runs of a message for a window of n cells, all checked, so that a malformed message can be
// refused before anything changes.
bool parseRuns(const local_map_t& msg, int64_t n, std::vector<Run>* out, std::string* error) {
  std::vector<Run>& runs = *out;
  runs.clear();
  size_t pos = 0;
  int64_t cursor = 0;
  while (pos < msg.runs.size()) {
    uint64_t skip = 0, length = 0;
    if (!getVarint(msg.runs, pos, skip) || !getVarint(msg.runs, pos, length) ||
        pos >= msg.runs.size()) {
      if (error) *error = "truncated run";
      return false;
    }
    const uint8_t state = msg.runs[pos++];
    if (state > static_cast<uint8_t>(Occupancy::kOccupied) || length == 0 ||
        skip > static_cast<uint64_t>(n) || length > static_cast<uint64_t>(n) ||
        cursor + static_cast<int64_t>(skip) + static_cast<int64_t>(length) > n) {
      if (error) *error = "run leaves the window or has a bad state";
      return false;
    }
    cursor += static_cast<int64_t>(skip);
    runs.push_back(Run{cursor, static_cast<int64_t>(length), state});
    cursor += static_cast<int64_t>(length);
  }
  return true;
}

}  // namespace

bool applyRuns(const local_map_t& msg, VoxelGrid& grid, std::string* error,
               std::vector<int64_t>* written) {
  std::vector<Run> runs;
  if (!parseRuns(msg, grid.numCells(), &runs, error)) return false;
  for (const Run& run : runs) {
    for (int64_t k = run.start; k < run.start + run.length; ++k) {
      grid.setLinear(k, static_cast<Occupancy>(run.state));
      if (written) written->push_back(k);
    }
  }
  return true;
}

LocalMapReceiver::Result LocalMapReceiver::apply(const local_map_t& msg, std::string* reason) {
  std::string why;
  if (!validateLocalMap(msg, &why)) {
    if (reason) *reason = why;
    return Result::kRejected;
  }
  const Eigen::Vector3i origin(msg.origin_index[0], msg.origin_index[1], msg.origin_index[2]);
  const Eigen::Vector3i size(msg.size[0], msg.size[1], msg.size[2]);
  if (synced_ && msg.map_seq <= last_seq_ && msg.kind == local_map_t::KIND_DELTA) {
    if (reason) *reason = "old map_seq " + std::to_string(msg.map_seq);
    return Result::kStale;
  }
  if (synced_ && msg.kind == local_map_t::KIND_KEYFRAME && msg.map_seq == last_seq_ &&
      msg.header.utime == last_utime_) {
    // The sender follows a delta with the keyframe of the same scan for receivers that lost
    // messages; one that applied the delta holds that map already (a restarted sender's
    // keyframe has another scan time and is applied).
    if (reason) *reason = "keyframe of map " + std::to_string(msg.map_seq) + ": already built";
    return Result::kAlreadyBuilt;
  }
  last_changed_.clear();
  const bool same_geometry =
      have_grid_ && size == grid_.size() && std::abs(msg.resolution_m - grid_.resolution()) <= 1e-9;
  if (msg.kind == local_map_t::KIND_KEYFRAME && same_geometry) {
    // Mostly what the deltas already built: write only the cells that differ, so that the
    // inflation of the whole window (tens of ms with a mapped ground) is not rebuilt while plan
    // requests wait. The result equals a fresh decode, whatever the grid held before.
    std::vector<Run> runs;
    if (!parseRuns(msg, grid_.numCells(), &runs, &why)) {
      if (reason) *reason = "keyframe: " + why;
      return Result::kRejected;
    }
    keyframe_cells_.assign(static_cast<size_t>(grid_.numCells()),
                           static_cast<uint8_t>(Occupancy::kUnknown));
    for (const Run& run : runs) {
      std::fill_n(keyframe_cells_.begin() + run.start, run.length, run.state);
    }
    grid_.shiftTo(origin);
    const std::vector<uint8_t>& cells = grid_.rawCells();
    for (int64_t i = 0; i < grid_.numCells(); ++i) {
      if (cells[i] != keyframe_cells_[i])
        grid_.setLinear(i, static_cast<Occupancy>(keyframe_cells_[i]));
    }
    synced_ = true;
    last_seq_ = msg.map_seq;
    last_utime_ = msg.header.utime;
    last_was_keyframe_ = true;
    return Result::kApplied;
  }
  if (msg.kind == local_map_t::KIND_KEYFRAME) {
    // Decode into a fresh grid first so that a malformed keyframe leaves the old map intact.
    VoxelGrid fresh(msg.resolution_m, origin, size);
    fresh.setInflationRadius(inflation_radius_);
    if (!applyRuns(msg, fresh, &why)) {
      if (reason) *reason = "keyframe: " + why;
      return Result::kRejected;
    }
    grid_ = std::move(fresh);
    have_grid_ = true;
    synced_ = true;
    last_seq_ = msg.map_seq;
    last_utime_ = msg.header.utime;
    last_was_keyframe_ = true;
    return Result::kApplied;
  }
  // Delta.
  if (!synced_) {
    if (reason) *reason = "delta before a keyframe";
    return Result::kWaitingForKeyframe;
  }
  // A delta holds every cell changed since its base (the sender repeats the last few deltas'
  // cells): any applied map from base_seq on is enough, so losing fewer messages in a row than
  // the sender repeats costs nothing.
  if (msg.base_seq > last_seq_) {
    synced_ = false;
    ++gaps_;
    if (reason)
      *reason = "gap: have map " + std::to_string(last_seq_) + ", delta " +
                std::to_string(msg.map_seq) + " needs base " + std::to_string(msg.base_seq) +
                " or later";
    return Result::kGap;
  }
  if (msg.map_seq != last_seq_ + 1) ++bridged_;
  if (size != grid_.size() || std::abs(msg.resolution_m - grid_.resolution()) > 1e-9) {
    synced_ = false;
    if (reason) *reason = "delta changes the window geometry";
    return Result::kRejected;
  }
  grid_.shiftTo(origin);
  if (!applyRuns(msg, grid_, &why, &last_changed_)) {
    // The window moved but no cell was written; the next keyframe resynchronises.
    synced_ = false;
    if (reason) *reason = "delta: " + why;
    return Result::kRejected;
  }
  last_seq_ = msg.map_seq;
  last_utime_ = msg.header.utime;
  last_was_keyframe_ = false;
  return Result::kApplied;
}

}  // namespace mmh
