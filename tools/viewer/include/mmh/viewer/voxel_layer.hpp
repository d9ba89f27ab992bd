// The occupied voxels the viewer shows: every cell ever seen occupied in a LOCAL_MAP window and
// not seen free or unknown since. Cells that leave the window stay (the ground station shows the
// whole mapped area), so each map message turns into a small list of added and removed voxels.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_set>
#include <vector>

#include "mmh/common/local_map_codec.hpp"
#include "mmh/local_map_t.hpp"

namespace mmh::viewer {

// Global voxel indices, flattened x0, y0, z0, x1, y1, z1, ...
struct VoxelChanges {
  std::vector<int32_t> added;
  std::vector<int32_t> removed;
  bool empty() const { return added.empty() && removed.empty(); }
};

class VoxelLayer {
 public:
  // Applies one LOCAL_MAP message. Returns false (and says why) if the receiver could not apply
  // it (a gap, a delta before a keyframe, a malformed map): the layer is then unchanged. The
  // keyframe of a map its delta already built changes nothing (true, no changes).
  bool apply(const local_map_t& msg, VoxelChanges* changes, std::string* reason = nullptr);

  double resolution() const { return resolution_; }
  size_t numOccupied() const { return occupied_.size(); }
  bool isOccupied(int32_t x, int32_t y, int32_t z) const { return occupied_.count(key(x, y, z)); }
  // Every occupied voxel, flattened as in VoxelChanges.
  std::vector<int32_t> allOccupied() const;

 private:
  static uint64_t key(int32_t x, int32_t y, int32_t z);
  static void unpack(uint64_t key, int32_t* x, int32_t* y, int32_t* z);
  void setCell(const Eigen::Vector3i& global, bool occupied, VoxelChanges* changes);
  void applyKeyframe(VoxelChanges* changes);
  void applyDelta(VoxelChanges* changes);

  LocalMapReceiver receiver_;
  std::unordered_set<uint64_t> occupied_;
  double resolution_ = 0.1;
};

}  // namespace mmh::viewer
