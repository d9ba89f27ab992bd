// Narrow-space test of the paper (Sec. III.B, "BothSideJudge"): probe both sides of a short
// segment along its normals; obstacles on both sides of either normal mean a narrow passage.
// Used by awareness (on the sensing ray) and by EAM (on its A* path).
#pragma once

#include <Eigen/Core>
#include <array>
#include <limits>
#include <vector>

#include "mmh/common/voxel_grid.hpp"

namespace mmh {

// The test for one grid and probe distance, with the probe offsets computed once and recent
// probe cells remembered: use it when many segments are tested (awareness, EAM). The grid must
// outlive the object and not change while it is used; one object per thread.
class NarrowSpaceProbe {
 public:
  NarrowSpaceProbe(const VoxelGrid& grid, double probe_dist_m);
  // See bothSidesBlocked below.
  bool bothSidesBlocked(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const;

 private:
  bool probeHits(const Eigen::Vector3d& p, const Eigen::Vector3d& n) const;
  const int* axisCells(int axis, double pc, double nc) const;
  static constexpr int kMaxBatch = 64;  // probes with more samples take the plain loop
  static constexpr int kMemoSlots = 4;  // one per probe direction of a segment
  struct AxisMemo {
    double pc = std::numeric_limits<double>::quiet_NaN(), nc = 0.0;  // NaN: never matches
    std::array<int, kMaxBatch> cells{};
  };

  const VoxelGrid& grid_;
  std::vector<double> offsets_;  // probe sample distances: half a voxel apart up to probe_dist_m
  mutable AxisMemo memo_[3][kMemoSlots];
  mutable int next_slot_[3] = {0, 0, 0};
};

// True when, from the midpoint of [a, b], occupied cells are found within probe_dist_m on both
// the left and the right (horizontal normal), or both above and below (vertical normal).
// Probes look at the uninflated occupancy (samples half a voxel apart); unknown counts as free.
bool bothSidesBlocked(const VoxelGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                      double probe_dist_m);

// Runs bothSidesBlocked on consecutive samples (one resolution apart) along a polyline.
// Returns true at the first narrow pair; *where receives its midpoint if given.
bool isPathNarrow(const VoxelGrid& grid, const std::vector<Eigen::Vector3d>& path,
                  double probe_dist_m, Eigen::Vector3d* where = nullptr);

}  // namespace mmh
