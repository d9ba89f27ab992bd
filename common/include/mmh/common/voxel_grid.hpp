// Dense occupancy window (unknown / free / occupied) around the vehicle, as rebuilt from
// LOCAL_MAP, with an incrementally maintained inflation by a radius for collision checks.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <vector>

namespace mmh {

enum class Occupancy : uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };

class VoxelGrid {
 public:
  VoxelGrid() = default;
  // A window of `size` voxels whose cell (0,0,0) is the global voxel `origin_index`; all unknown.
  VoxelGrid(double resolution_m, const Eigen::Vector3i& origin_index, const Eigen::Vector3i& size);

  // --- geometry -------------------------------------------------------------------------
  double resolution() const { return resolution_; }
  const Eigen::Vector3i& originIndex() const { return origin_; }
  const Eigen::Vector3i& size() const { return size_; }
  int64_t numCells() const { return static_cast<int64_t>(cells_.size()); }
  bool valid() const { return !cells_.empty(); }

  // Global voxel index of a world point: floor(p / resolution). Inline, with centerOfLocal:
  // every collision check and search calls them per sample or cell.
  Eigen::Vector3i globalIndexOf(const Eigen::Vector3d& p) const {
    return Eigen::Vector3i(static_cast<int>(std::floor(p.x() / resolution_)),
                           static_cast<int>(std::floor(p.y() / resolution_)),
                           static_cast<int>(std::floor(p.z() / resolution_)));
  }
  Eigen::Vector3i localIndexOf(const Eigen::Vector3d& p) const {
    return globalIndexOf(p) - origin_;
  }
  Eigen::Vector3d centerOfLocal(const Eigen::Vector3i& local) const {
    return ((origin_ + local).cast<double>() + Eigen::Vector3d::Constant(0.5)) * resolution_;
  }
  bool inWindow(const Eigen::Vector3i& local) const {
    return local.x() >= 0 && local.y() >= 0 && local.z() >= 0 && local.x() < size_.x() &&
           local.y() < size_.y() && local.z() < size_.z();
  }
  bool containsPoint(const Eigen::Vector3d& p) const { return inWindow(localIndexOf(p)); }
  int64_t linearIndex(const Eigen::Vector3i& local) const {
    return local.x() +
           static_cast<int64_t>(size_.x()) * (local.y() + int64_t{size_.y()} * local.z());
  }
  Eigen::Vector3i localFromLinear(int64_t index) const;
  // World-frame corners of the window.
  Eigen::Vector3d minCorner() const { return origin_.cast<double>() * resolution_; }
  Eigen::Vector3d maxCorner() const { return (origin_ + size_).cast<double>() * resolution_; }

  // --- occupancy ------------------------------------------------------------------------
  Occupancy at(const Eigen::Vector3i& local) const {
    return inWindow(local) ? static_cast<Occupancy>(cells_[linearIndex(local)])
                           : Occupancy::kUnknown;
  }
  Occupancy atLinear(int64_t index) const { return static_cast<Occupancy>(cells_[index]); }
  Occupancy atPoint(const Eigen::Vector3d& p) const { return at(localIndexOf(p)); }
  void set(const Eigen::Vector3i& local, Occupancy state) { setLinear(linearIndex(local), state); }
  void setLinear(int64_t index, Occupancy state);
  void clear();  // everything unknown
  int64_t numOccupied() const { return num_occupied_; }
  const std::vector<uint8_t>& rawCells() const { return cells_; }

  // Move the window so that its cell (0,0,0) is `new_origin`: the overlap keeps its state,
  // cells that enter are unknown.
  void shiftTo(const Eigen::Vector3i& new_origin);

  // --- inflation ------------------------------------------------------------------------
  // Cells within `radius_m` (centre to centre) of an occupied cell are "blocked". Changing the
  // radius rebuilds the counts; later updates are incremental.
  void setInflationRadius(double radius_m);
  double inflationRadius() const { return inflation_radius_; }
  // Offsets (in cells) whose centres lie within radius_m of a cell's centre: the inflation
  // kernel, for checks that need another radius than the grid's own.
  static std::vector<Eigen::Vector3i> offsetsWithin(double radius_m, double resolution_m);
  bool isBlocked(const Eigen::Vector3i& local) const {
    return inWindow(local) && blocked_count_[linearIndex(local)] > 0;
  }
  bool isBlockedLinear(int64_t index) const { return blocked_count_[index] > 0; }
  // Per cell, the number of occupied cells within the inflation radius (> 0: blocked); for
  // scans that read whole rows.
  const uint16_t* blockedCounts() const { return blocked_count_.data(); }
  bool isBlockedPoint(const Eigen::Vector3d& p) const { return isBlocked(localIndexOf(p)); }
  bool isOccupiedPoint(const Eigen::Vector3d& p) const {
    return atPoint(p) == Occupancy::kOccupied;
  }

 private:
  void addToInflation(int64_t index, int delta);
  void rebuildInflation();

  double resolution_ = 0.1;
  Eigen::Vector3i origin_ = Eigen::Vector3i::Zero();
  Eigen::Vector3i size_ = Eigen::Vector3i::Zero();
  std::vector<uint8_t> cells_;
  std::vector<uint16_t> blocked_count_;
  int64_t num_occupied_ = 0;
  double inflation_radius_ = 0.0;
  std::vector<Eigen::Vector3i> kernel_;  // offsets within the inflation radius
};

}  // namespace mmh
