// A* guide paths around the colliding stretches of an EAM trajectory (the "A* path" that gives
// EGO-Planner's anchor pairs): first in the voxel layers of the stretch and a box around it,
// then in the whole geofence band; again with a cost on slot cells (gaps too narrow for a smooth
// curve at speed) when the shortest path threads one.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "mmh/common/grid_astar.hpp"
#include "mmh/common/voxel_grid.hpp"
#include "mmh/eam/eam_params.hpp"

namespace mmh::eam {

struct GuideStats {
  int calls = 0;  // A* searches
  int64_t expansions = 0;
  double us = 0.0;  // wall-clock time in A*
};

// Does the cell lie in a slot: inflated obstacles within `reach` voxels on both sides along x,
// y or z, or within `diag_reach` voxels on both sides along a horizontal diagonal?
bool inSlot(const VoxelGrid& grid, const Eigen::Vector3i& cell, int reach, int diag_reach);

class GuideSearch {
 public:
  explicit GuideSearch(const EamParams& params) : params_(params) {}

  // Path from `from` to `goal` (free points of the curve around a stretch whose altitude spans
  // [z_lo, z_hi]). avoid_slots: use the slot cost from the start rather than only when the
  // shortest path threads a slot; slot_width_m: what counts as a slot (astar_slot_width_m
  // normally).
  // Sizes the per-cell arrays for this grid now (tens of MB for a full window), so that the
  // first request after a new map does not pay for it.
  void prepare(const VoxelGrid& grid);

  AStarResult find(const VoxelGrid& grid, const Eigen::Vector3d& from, const Eigen::Vector3d& goal,
                   double z_lo, double z_hi, bool avoid_slots, double slot_width_m,
                   GuideStats* stats);

 private:
  EamParams params_;
  GridAStar astar_;                    // keeps its per-cell arrays between calls
  std::vector<int8_t> slot_memo_;      // per cell: 0 unknown, 1 in a slot, 2 not
  std::vector<int64_t> slot_touched_;  // cells to reset after a search
};

}  // namespace mmh::eam
