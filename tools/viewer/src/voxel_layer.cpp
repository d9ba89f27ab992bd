#include "mmh/viewer/voxel_layer.hpp"

namespace mmh::viewer {
namespace {
// 21 bits per axis around zero: +-2^20 voxels, 100 km at 0.1 m, beyond the validated 10^6 m
// coordinates only for resolutions under 1 m, which LOCAL_MAP validation bounds anyway.
constexpr int64_t kAxisOffset = int64_t{1} << 20;
constexpr uint64_t kAxisMask = (uint64_t{1} << 21) - 1;
}  // namespace

uint64_t VoxelLayer::key(int32_t x, int32_t y, int32_t z) {
  const auto axis = [](int32_t v) { return static_cast<uint64_t>(v + kAxisOffset) & kAxisMask; };
  return axis(x) | (axis(y) << 21) | (axis(z) << 42);
}

void VoxelLayer::unpack(uint64_t key, int32_t* x, int32_t* y, int32_t* z) {
  const auto axis = [key](int shift) {
    return static_cast<int32_t>(static_cast<int64_t>((key >> shift) & kAxisMask) - kAxisOffset);
  };
  *x = axis(0);
  *y = axis(21);
  *z = axis(42);
}

bool VoxelLayer::apply(const local_map_t& msg, VoxelChanges* changes, std::string* reason) {
  changes->added.clear();
  changes->removed.clear();
  const LocalMapReceiver::Result result = receiver_.apply(msg, reason);
  if (result == LocalMapReceiver::Result::kAlreadyBuilt) return true;  // nothing changed
  if (result != LocalMapReceiver::Result::kApplied) return false;
  resolution_ = receiver_.grid().resolution();
  if (receiver_.lastWasKeyframe())
    applyKeyframe(changes);
  else
    applyDelta(changes);
  return true;
}

void VoxelLayer::setCell(const Eigen::Vector3i& global, bool occupied, VoxelChanges* changes) {
  const uint64_t k = key(global.x(), global.y(), global.z());
  std::vector<int32_t>* list = nullptr;
  if (occupied && occupied_.insert(k).second) list = &changes->added;
  if (!occupied && occupied_.erase(k) > 0) list = &changes->removed;
  if (list) list->insert(list->end(), {global.x(), global.y(), global.z()});
}

void VoxelLayer::applyKeyframe(VoxelChanges* changes) {
  const VoxelGrid& grid = receiver_.grid();
  const Eigen::Vector3i& origin = grid.originIndex();
  // Voxels inside the window that the keyframe no longer calls occupied.
  std::vector<uint64_t> gone;
  for (uint64_t k : occupied_) {
    Eigen::Vector3i global;
    unpack(k, &global.x(), &global.y(), &global.z());
    const Eigen::Vector3i local = global - origin;
    if (grid.inWindow(local) && grid.at(local) != Occupancy::kOccupied) gone.push_back(k);
  }
  for (uint64_t k : gone) {
    Eigen::Vector3i global;
    unpack(k, &global.x(), &global.y(), &global.z());
    setCell(global, false, changes);
  }
  const std::vector<uint8_t>& cells = grid.rawCells();
  for (int64_t i = 0; i < static_cast<int64_t>(cells.size()); ++i) {
    if (cells[i] == static_cast<uint8_t>(Occupancy::kOccupied))
      setCell(origin + grid.localFromLinear(i), true, changes);
  }
}

void VoxelLayer::applyDelta(VoxelChanges* changes) {
  const VoxelGrid& grid = receiver_.grid();
  for (int64_t i : receiver_.lastChangedCells())
    setCell(grid.originIndex() + grid.localFromLinear(i), grid.atLinear(i) == Occupancy::kOccupied,
            changes);
}

std::vector<int32_t> VoxelLayer::allOccupied() const {
  std::vector<int32_t> out;
  out.reserve(occupied_.size() * 3);
  for (uint64_t k : occupied_) {
    int32_t x, y, z;
    unpack(k, &x, &y, &z);
    out.insert(out.end(), {x, y, z});
  }
  return out;
}

}  // namespace mmh::viewer
