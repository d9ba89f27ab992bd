// Point -> cell lookups for the awareness / narrow-space hot loops: exactly the cell of
// VoxelGrid::globalIndexOf (floor(p / resolution)), without a libm floor call per coordinate
// (that call cost more than the rest of the lookup). Private to mmh_common.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>

#include "mmh/common/voxel_grid.hpp"

namespace mmh {
namespace detail {

class CellLookup {
 public:
  explicit CellLookup(const VoxelGrid& grid)
      : grid_(grid),
        cells_(grid.rawCells().data()),
        res_(grid.resolution()),
        origin_(grid.originIndex()),
        size_(grid.size()) {}

  // floor(x / resolution) exactly as VoxelGrid computes it (the same correctly rounded
  // division), with the floor done by truncation instead of a libm call.
  int floorIndex(double x) const {
    const double q = x / res_;
    if (!(std::abs(q) < 1e9)) return outside(x);
    const int k = static_cast<int>(q);
    return q < k ? k - 1 : k;
  }

  const Eigen::Vector3i& origin() const { return origin_; }
  const Eigen::Vector3i& size() const { return size_; }
  bool occupiedLinear(int64_t i) const {
    return cells_[i] == static_cast<uint8_t>(Occupancy::kOccupied);
  }

  // Linear index of the window cell containing p, or -1 outside the window.
  int64_t linearOf(double x, double y, double z) const {
    const int ix = floorIndex(x) - origin_.x();
    if (ix < 0 || ix >= size_.x()) return -1;
    const int iy = floorIndex(y) - origin_.y();
    if (iy < 0 || iy >= size_.y()) return -1;
    const int iz = floorIndex(z) - origin_.z();
    if (iz < 0 || iz >= size_.z()) return -1;
    return ix + static_cast<int64_t>(size_.x()) * (iy + static_cast<int64_t>(size_.y()) * iz);
  }
  int64_t linearOf(const Eigen::Vector3d& p) const { return linearOf(p.x(), p.y(), p.z()); }

  bool blocked(const Eigen::Vector3d& p) const {
    const int64_t i = linearOf(p);
    return i >= 0 && grid_.isBlockedLinear(i);
  }

 private:
  // Non-finite or absurd coordinates: a cell far outside any window.
  int outside(double x) const {
    if (!std::isfinite(x)) return INT32_MIN / 2;
    const double q = std::floor(x / res_);
    return q > 0 ? INT32_MAX / 2 : INT32_MIN / 2;
  }

  const VoxelGrid& grid_;
  const uint8_t* cells_;
  double res_;
  Eigen::Vector3i origin_, size_;
};

}  // namespace detail
}  // namespace mmh
