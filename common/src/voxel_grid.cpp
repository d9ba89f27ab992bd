#include "mmh/common/voxel_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mmh {

VoxelGrid::VoxelGrid(double resolution_m, const Eigen::Vector3i& origin_index,
                     const Eigen::Vector3i& size)
    : resolution_(resolution_m), origin_(origin_index), size_(size) {
  if (!(resolution_m > 0.0) || (size.array() <= 0).any()) {
    throw std::invalid_argument("VoxelGrid: resolution and size must be positive");
  }
  const int64_t n = int64_t{size.x()} * size.y() * size.z();
  cells_.assign(n, static_cast<uint8_t>(Occupancy::kUnknown));
  blocked_count_.assign(n, 0);
  kernel_ = {Eigen::Vector3i::Zero()};
}

Eigen::Vector3i VoxelGrid::globalIndexOf(const Eigen::Vector3d& p) const {
  return Eigen::Vector3i(static_cast<int>(std::floor(p.x() / resolution_)),
                         static_cast<int>(std::floor(p.y() / resolution_)),
                         static_cast<int>(std::floor(p.z() / resolution_)));
}

Eigen::Vector3d VoxelGrid::centerOfLocal(const Eigen::Vector3i& local) const {
  return ((origin_ + local).cast<double>() + Eigen::Vector3d::Constant(0.5)) * resolution_;
}

Eigen::Vector3i VoxelGrid::localFromLinear(int64_t index) const {
  const int64_t plane = int64_t{size_.x()} * size_.y();
  int z = static_cast<int>(index / plane);
  int64_t rest = index - z * plane;
  int y = static_cast<int>(rest / size_.x());
  int x = static_cast<int>(rest - int64_t{y} * size_.x());
  return Eigen::Vector3i(x, y, z);
}

void VoxelGrid::setLinear(int64_t index, Occupancy state) {
  const auto old_state = static_cast<Occupancy>(cells_[index]);
  if (old_state == state) return;
  cells_[index] = static_cast<uint8_t>(state);
  if (old_state == Occupancy::kOccupied) {
    --num_occupied_;
    addToInflation(index, -1);
  } else if (state == Occupancy::kOccupied) {
    ++num_occupied_;
    addToInflation(index, +1);
  }
}

void VoxelGrid::clear() {
  std::fill(cells_.begin(), cells_.end(), static_cast<uint8_t>(Occupancy::kUnknown));
  std::fill(blocked_count_.begin(), blocked_count_.end(), 0);
  num_occupied_ = 0;
}

void VoxelGrid::addToInflation(int64_t index, int delta) {
  const Eigen::Vector3i centre = localFromLinear(index);
  for (const Eigen::Vector3i& offset : kernel_) {
    const Eigen::Vector3i n = centre + offset;
    if (!inWindow(n)) continue;
    uint16_t& count = blocked_count_[linearIndex(n)];
    count = static_cast<uint16_t>(count + delta);
  }
}

void VoxelGrid::rebuildInflation() {
  std::fill(blocked_count_.begin(), blocked_count_.end(), 0);
  for (int64_t i = 0; i < numCells(); ++i) {
    if (cells_[i] == static_cast<uint8_t>(Occupancy::kOccupied)) addToInflation(i, +1);
  }
}

void VoxelGrid::setInflationRadius(double radius_m) {
  if (!(radius_m >= 0.0)) throw std::invalid_argument("VoxelGrid: negative inflation radius");
  inflation_radius_ = radius_m;
  kernel_.clear();
  const int r = static_cast<int>(std::floor(radius_m / resolution_ + 1e-9));
  const double r2 = (radius_m / resolution_) * (radius_m / resolution_) + 1e-9;
  for (int z = -r; z <= r; ++z)
    for (int y = -r; y <= r; ++y)
      for (int x = -r; x <= r; ++x)
        if (x * x + y * y + z * z <= r2) kernel_.emplace_back(x, y, z);
  if (valid()) rebuildInflation();
}

void VoxelGrid::shiftTo(const Eigen::Vector3i& new_origin) {
  if (new_origin == origin_ || !valid()) {
    origin_ = new_origin;
    return;
  }
  const Eigen::Vector3i shift = new_origin - origin_;  // old local = new local + shift
  // Occupied cells leaving the window take their inflation with them.
  for (int64_t i = 0; i < numCells(); ++i) {
    if (cells_[i] != static_cast<uint8_t>(Occupancy::kOccupied)) continue;
    if (!inWindow(localFromLinear(i) - shift)) {
      cells_[i] = static_cast<uint8_t>(Occupancy::kUnknown);
      --num_occupied_;
      addToInflation(i, -1);
    }
  }
  std::vector<uint8_t> cells(cells_.size(), static_cast<uint8_t>(Occupancy::kUnknown));
  std::vector<uint16_t> counts(blocked_count_.size(), 0);
  const Eigen::Vector3i lo = (-shift).cwiseMax(0);
  const Eigen::Vector3i hi = (size_ - shift).cwiseMin(size_);  // exclusive, new local
  for (int z = lo.z(); z < hi.z(); ++z) {
    for (int y = lo.y(); y < hi.y(); ++y) {
      if (hi.x() <= lo.x()) continue;
      const int64_t dst = linearIndex(Eigen::Vector3i(lo.x(), y, z));
      const int64_t src = linearIndex(Eigen::Vector3i(lo.x(), y, z) + shift);
      std::copy_n(cells_.begin() + src, hi.x() - lo.x(), cells.begin() + dst);
      std::copy_n(blocked_count_.begin() + src, hi.x() - lo.x(), counts.begin() + dst);
    }
  }
  cells_.swap(cells);
  blocked_count_.swap(counts);
  origin_ = new_origin;
}

}  // namespace mmh
