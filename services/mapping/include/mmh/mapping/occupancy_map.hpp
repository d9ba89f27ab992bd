// The probabilistic map: an OctoMap OcTree (OctoMap's sensor model: log-odds hits and misses,
// clamped) that holds everything mapped, plus a rolling window around the vehicle — the part
// published as LOCAL_MAP — through which every scan is inserted.
//
// Why the window: OctoMap's own insertPointCloud costs about a microsecond per voxel (hashing
// the ray keys and walking the tree from the root for each), and a depth frame touches ~40,000
// voxels, far over the 5 ms budget. Here rays are traversed in a dense ring buffer over the
// window that caches each voxel's log-odds and a pointer to its OcTree leaf: a voxel that is
// already clamped costs nothing, and changed voxels are written back to their leaves in batches
// (flush(): before the window moves and at every keyframe), once however often they changed;
// only new voxels walk the tree (OcTree::setNodeValue). The tree is the store (lazy inner
// nodes); subtrees left behind by the moving window are pruned as OctoMap does.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/voxel_grid.hpp"
#include "mmh/mapping/mapping_params.hpp"
#include "mmh/mapping/scan_filter.hpp"

namespace octomap {
class OcTree;
class OcTreeNode;
}  // namespace octomap

namespace mmh::mapping {

struct InsertStats {
  size_t rays = 0;            // rays cast (returns + free rays)
  size_t cells_free = 0;      // distinct voxels that received a miss
  size_t cells_occupied = 0;  // distinct voxels that received a hit
  size_t cells_updated = 0;   // voxels whose log-odds changed (not already clamped)
  size_t ends_outside = 0;    // returns outside the window (not inserted)
};

class OccupancyMap {
 public:
  explicit OccupancyMap(const MappingParams& params);
  ~OccupancyMap();
  OccupancyMap(const OccupancyMap&) = delete;
  OccupancyMap& operator=(const OccupancyMap&) = delete;

  // Places the window around `position` the first time, then moves it whenever `position` is
  // more than window_recenter_m (any axis) off its centre. Cells that enter take their state
  // from the tree and count as changes. Returns true if the window was placed or moved.
  bool followVehicle(const Eigen::Vector3d& position);

  // Inserts a filtered scan inside the window: a miss for every voxel the rays cross before
  // their end, a hit for every return's voxel (hits win over misses within a scan, as in
  // OctoMap's insertPointCloud). Requires a window (followVehicle first).
  InsertStats insert(const FilteredScan& scan);

  // Window cells whose state changed since the last call (sorted, with their new state), for a
  // LOCAL_MAP delta. Clears the list.
  std::vector<CellChange> takeChanges();
  void clearChanges() { changed_.clear(); }
  // The same in two steps, for deltas that repeat earlier changes: the changed cells (global
  // cell keys, unsorted, possibly repeated), cleared; and the current window state of any such
  // cells that are inside the window, sorted by window index.
  std::vector<int64_t> takeChangedCells();
  std::vector<CellChange> windowChangesOf(const std::vector<int64_t>& cells) const;

  bool hasWindow() const { return has_window_; }
  // The published window: cell (0,0,0) is global voxel windowOrigin(); states (unknown / free /
  // occupied, as Occupancy) in VoxelGrid order (x fastest), i.e. what LOCAL_MAP receivers hold.
  const Eigen::Vector3i& windowOrigin() const { return origin_; }
  const Eigen::Vector3i& windowSize() const { return size_; }
  double resolution() const { return res_; }
  const std::vector<uint8_t>& windowStates() const { return states_; }
  Occupancy stateAt(const Eigen::Vector3d& p) const;
  // A VoxelGrid copy of the window (allocates; for tests and tools).
  VoxelGrid window() const;
  // State of any point: from the window inside it, from the tree outside.
  Occupancy query(const Eigen::Vector3d& p) const;
  // Writes the window's changed log-odds to their tree leaves (creating leaves for new voxels).
  // Done before every window move and by Mapper::maintain() after every keyframe; returns the
  // leaves created.
  size_t flush();
  // The tree; its leaves inside the window are current after flush().
  const octomap::OcTree& octree() const;
  size_t octreeLeaves() const;
  // Collapses identical siblings in the tree outside the window (OctoMap's pruning).
  void pruneOutsideWindow();

 private:
  int64_t ringIndex(const Eigen::Vector3i& g) const;
  // Bricks of 8 x 8 x 8 cells are contiguous, so that the cells a scan touches share cache lines.
  int64_t ringSlot(int rx, int ry, int rz) const {
    return ((((static_cast<int64_t>(rz >> 3) * bricks_.y()) + (ry >> 3)) * bricks_.x() + (rx >> 3))
            << 9) |
           ((rz & 7) << 6) | ((ry & 7) << 3) | (rx & 7);
  }
  bool inWindow(const Eigen::Vector3i& g) const {
    return (g.array() >= origin_.array()).all() && (g.array() < (origin_ + size_).array()).all();
  }
  void resetBox(const Eigen::Vector3i& lo, const Eigen::Vector3i& hi);  // global, hi exclusive
  void loadBox(const Eigen::Vector3i& lo, const Eigen::Vector3i& hi);
  // Global cell of a ring slot (the one inside the window).
  Eigen::Vector3i cellOfSlot(uint32_t slot) const;
  int64_t windowIndex(const Eigen::Vector3i& g) const {
    return (g.x() - origin_.x()) +
           static_cast<int64_t>(size_.x()) *
               ((g.y() - origin_.y()) + static_cast<int64_t>(size_.y()) * (g.z() - origin_.z()));
  }
  void shiftStates(const Eigen::Vector3i& shift);
  void setKnown(int64_t ring, const Eigen::Vector3i& g, float log_odds, octomap::OcTreeNode* node);
  // This scan's marks in stamp_.
  struct ScanStamps {
    uint8_t free, hit, kept;
  };
  // Adds the cells the ray crosses to free_list_, but none this scan stamped already (freed, hit
  // or kept: stamps at or above free_stamp).
  void castFree(const Eigen::Vector3d& origin, const Eigen::Vector3d& end, uint8_t free_stamp);
  // Stamps as kept the neighbours of this scan's hit cells that are mapped occupied: this scan
  // does not clear them.
  void keepOccupiedBesideHits(ScanStamps marks);
  void apply(uint32_t slot, float delta, InsertStats* stats);
  Occupancy stateOf(float log_odds) const {
    return log_odds > occ_threshold_ ? Occupancy::kOccupied : Occupancy::kFree;
  }
  void markChanged(const Eigen::Vector3i& g);

  MappingParams params_;
  double res_;
  float log_hit_, log_miss_, clamp_min_, clamp_max_, occ_threshold_;
  struct Tree;
  std::unique_ptr<Tree> tree_;
  Eigen::Vector3i origin_ = Eigen::Vector3i::Zero();
  Eigen::Vector3i size_ = Eigen::Vector3i::Zero();
  bool has_window_ = false;
  std::vector<uint8_t> states_;  // published state per window cell (VoxelGrid order)
  // Ring buffer over the window: global cell g lives in slot (g mod ring_) per axis, stored in
  // bricks of 8^3 cells.
  Eigen::Vector3i ring_ = Eigen::Vector3i::Zero(), bricks_ = Eigen::Vector3i::Zero();
  std::vector<octomap::OcTreeNode*> node_;  // leaf at full depth, or null (unknown / pruned)
  std::vector<float> log_odds_;             // NaN = unknown
  std::vector<uint8_t> stamp_;              // per-scan marks: 3 gen = free, + 1 = hit, + 2 = kept
  uint8_t generation_ = 0;
  std::vector<uint32_t> occupied_list_, free_list_;  // ring slots touched by the scan
  std::vector<uint8_t> dirty_;                       // per slot: changed since the last flush
  std::vector<uint32_t> dirty_list_;
  std::vector<int64_t> changed_;  // packed global cells whose state changed
  bool moved_since_prune_ = false;
  // Bounding box (inclusive) of the windows since the last pruning.
  Eigen::Vector3i region_lo_ = Eigen::Vector3i::Zero(), region_hi_ = Eigen::Vector3i::Zero();
};

}  // namespace mmh::mapping
