// A* on the inflated voxel grid, 26-connected, bounded by a node budget, with line-of-sight
// path shortening. Unknown space is free unless the options say otherwise.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "mmh/common/voxel_grid.hpp"

namespace mmh {

struct AStarOptions {
  int64_t max_expansions = 200000;
  bool unknown_is_free = true;
  // Search only inside this world box (e.g. the altitude band of the geofence).
  Eigen::Vector3d min_bound = Eigen::Vector3d::Constant(-1e9);
  Eigen::Vector3d max_bound = Eigen::Vector3d::Constant(1e9);
  // When the start lies in the inflated (but not occupied) zone, cells within this distance of it
  // may be crossed so that the vehicle can leave the margin it is in.
  double start_escape_radius_m = 0.0;
  // ... and only those whose centres keep this distance from the occupied cells (the start cell
  // itself always may): the way out leads outwards. The same rule as SOM's corridor escape zone.
  double start_escape_min_distance_m = 0.0;
  // Weight on the heuristic: above 1 the search expands far fewer cells and returns a path at
  // most this factor longer than the shortest (weighted A*); 1 (+ a tie-breaking 1e-3) is exact.
  double heuristic_weight = 1.0;
  // Optional extra cost (in cells, >= 0) of entering a cell (local index, linear index), e.g. to
  // keep the path away from obstacles. The heuristic stays admissible.
  std::function<double(const Eigen::Vector3i&, int64_t)> extra_step_cost;
};

struct AStarResult {
  enum class Status { kFound, kStartBlocked, kGoalBlocked, kOutOfWindow, kNoPath, kBudgetExceeded };
  Status status = Status::kNoPath;
  std::vector<Eigen::Vector3d> path;  // start, cell centres..., goal
  int64_t expansions = 0;
  bool ok() const { return status == Status::kFound; }
};

const char* toString(AStarResult::Status status);

class GridAStar {
 public:
  AStarResult search(const VoxelGrid& grid, const Eigen::Vector3d& start,
                     const Eigen::Vector3d& goal, const AStarOptions& options = {});
  // Sizes the per-cell arrays for a grid of this many cells ahead of time: the first search on a
  // window otherwise allocates and clears them (tens of ms for a 32 x 32 x 4 m window at 0.1 m),
  // which a node should pay when a map arrives, not inside a planning call.
  void reserve(int64_t num_cells);

 private:
  // Per-cell search state in one record (one cache line per neighbour visited), reused across
  // searches (a generation stamp marks stale entries). `extra` is the cell's extra step cost,
  // asked once per search when the cell is first reached, not once per edge into it.
  struct CellState {
    float g = 0.f;
    int32_t parent = -1;
    uint32_t stamp = 0;
    float extra = 0.f;
  };
  std::vector<CellState> cells_;
  uint32_t generation_ = 0;
  struct OpenEntry {
    float f;
    int32_t index;
    bool operator>(const OpenEntry& o) const { return f > o.f; }
  };
  std::vector<OpenEntry> open_;  // the open list's storage, reused across searches
};

// Removes intermediate points while the straight segment between kept points stays free and
// out of every point `keep_out` (if given) is true for: the space the search paid extra to avoid
// (AStarOptions::extra_step_cost), which a shortcut would otherwise cross after all. Steps
// between neighbouring points of `path` are always kept.
std::vector<Eigen::Vector3d> shortenPath(
    const VoxelGrid& grid, const std::vector<Eigen::Vector3d>& path,
    const std::function<bool(const Eigen::Vector3d&)>& keep_out = {});

double pathLength(const std::vector<Eigen::Vector3d>& path);

}  // namespace mmh
