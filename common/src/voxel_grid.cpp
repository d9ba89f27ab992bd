#include "mmh/common/voxel_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
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
  kernel_ = offsetsWithin(radius_m, resolution_);
  if (valid()) rebuildInflation();
}

std::vector<Eigen::Vector3i> VoxelGrid::offsetsWithin(double radius_m, double resolution_m) {
  std::vector<Eigen::Vector3i> offsets;
  const int r = static_cast<int>(std::floor(radius_m / resolution_m + 1e-9));
  const double r2 = (radius_m / resolution_m) * (radius_m / resolution_m) + 1e-9;
  for (int z = -r; z <= r; ++z)
    for (int y = -r; y <= r; ++y)
      for (int x = -r; x <= r; ++x)
        if (x * x + y * y + z * z <= r2) offsets.emplace_back(x, y, z);
  return offsets;
}

namespace {

// Calls f(x, y, z) for every cell of the box [outer_lo, outer_hi) that is not in the box
// [inner_lo, inner_hi): the thin shell a window move touches, without visiting the rest.
template <typename F>
void forEachInShell(const Eigen::Vector3i& outer_lo, const Eigen::Vector3i& outer_hi,
                    const Eigen::Vector3i& inner_lo, const Eigen::Vector3i& inner_hi, F&& f) {
  for (int z = outer_lo.z(); z < outer_hi.z(); ++z) {
    for (int y = outer_lo.y(); y < outer_hi.y(); ++y) {
      const bool row_crosses_inner = z >= inner_lo.z() && z < inner_hi.z() && y >= inner_lo.y() &&
                                     y < inner_hi.y() && inner_lo.x() < inner_hi.x();
      if (!row_crosses_inner) {
        for (int x = outer_lo.x(); x < outer_hi.x(); ++x) f(x, y, z);
        continue;
      }
      for (int x = outer_lo.x(); x < std::min(inner_lo.x(), outer_hi.x()); ++x) f(x, y, z);
      for (int x = std::max(inner_hi.x(), outer_lo.x()); x < outer_hi.x(); ++x) f(x, y, z);
    }
  }
}

}  // namespace

void VoxelGrid::shiftTo(const Eigen::Vector3i& new_origin) {
  if (new_origin == origin_ || !valid()) {
    origin_ = new_origin;
    return;
  }
  const Eigen::Vector3i shift = new_origin - origin_;       // old local = new local + shift
  if ((shift.cwiseAbs().array() >= size_.array()).any()) {  // nothing overlaps
    clear();
    origin_ = new_origin;
    return;
  }
  const Eigen::Vector3i zero = Eigen::Vector3i::Zero();
  const Eigen::Vector3i lo = (-shift).cwiseMax(0);             // overlap, new local coordinates
  const Eigen::Vector3i hi = (size_ - shift).cwiseMin(size_);  // exclusive
  // 1. Occupied cells leaving the window take their inflation with them.
  forEachInShell(zero, size_, lo + shift, hi + shift, [&](int x, int y, int z) {
    const int64_t i = linearIndex(Eigen::Vector3i(x, y, z));
    if (cells_[i] != static_cast<uint8_t>(Occupancy::kOccupied)) return;
    cells_[i] = static_cast<uint8_t>(Occupancy::kUnknown);
    --num_occupied_;
    addToInflation(i, -1);
  });
  // 2. Move the overlap in place, row by row; the copy order keeps unread rows intact.
  const int64_t delta = linearIndex(shift);  // source index - destination index
  const int row = hi.x() - lo.x();
  auto move_row = [&](int y, int z) {
    const int64_t dst = linearIndex(Eigen::Vector3i(lo.x(), y, z));
    std::memmove(&cells_[dst], &cells_[dst + delta], row * sizeof(uint8_t));
    std::memmove(&blocked_count_[dst], &blocked_count_[dst + delta], row * sizeof(uint16_t));
  };
  if (delta > 0) {
    for (int z = lo.z(); z < hi.z(); ++z)
      for (int y = lo.y(); y < hi.y(); ++y) move_row(y, z);
  } else {
    for (int z = hi.z() - 1; z >= lo.z(); --z)
      for (int y = hi.y() - 1; y >= lo.y(); --y) move_row(y, z);
  }
  origin_ = new_origin;
  // 3. Cells that entered are unknown, with no inflation yet.
  forEachInShell(zero, size_, lo, hi, [&](int x, int y, int z) {
    const int64_t i = linearIndex(Eigen::Vector3i(x, y, z));
    cells_[i] = static_cast<uint8_t>(Occupancy::kUnknown);
    blocked_count_[i] = 0;
  });
  // 4. Occupied cells near the faces that moved in also inflate into the cells that entered.
  int reach = 0;
  for (const Eigen::Vector3i& k : kernel_) reach = std::max(reach, k.cwiseAbs().maxCoeff());
  if (reach == 0) return;
  auto in_overlap = [&](const Eigen::Vector3i& c) {
    return (c.array() >= lo.array()).all() && (c.array() < hi.array()).all();
  };
  // Only the faces where cells entered matter.
  Eigen::Vector3i inner_lo = lo, inner_hi = hi;
  for (int a = 0; a < 3; ++a) {
    if (lo[a] > 0) inner_lo[a] = std::min(hi[a], lo[a] + reach);
    if (hi[a] < size_[a]) inner_hi[a] = std::max(inner_lo[a], hi[a] - reach);
  }
  forEachInShell(lo, hi, inner_lo, inner_hi, [&](int x, int y, int z) {
    const Eigen::Vector3i c(x, y, z);
    if (cells_[linearIndex(c)] != static_cast<uint8_t>(Occupancy::kOccupied)) return;
    for (const Eigen::Vector3i& k : kernel_) {
      const Eigen::Vector3i n = c + k;
      if (inWindow(n) && !in_overlap(n)) ++blocked_count_[linearIndex(n)];
    }
  });
}

}  // namespace mmh
