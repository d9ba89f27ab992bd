// The A* step cost that keeps SOM's path away from obstacles where a wider way is not much
// longer. A* on the inflated grid is happy to thread the narrowest gap between two trunks; the
// corridor there is a string of tiny polytopes and the optimiser must brake to pass through them.
// A path through the middle of a wide gap, or round the outside, gives large polytopes and a
// faster, smoother trajectory.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <vector>

#include "mmh/common/voxel_grid.hpp"

namespace mmh::som {

struct ClearanceCostParams {
  double cost_cells = 5.0;  // extra A* cost of a cell next to the inflated obstacles (0: off)
  double width_m = 0.3;     // ... falling linearly to 0 at this clearance from them
  // None within this distance of the start: there the start state decides the way, and a cost
  // would only push the path into the unseen space beside the vehicle.
  double free_radius_m = 2.5;
  // Plan along both paths (with and without the cost) and keep the cheaper answer by the
  // optimiser's own measure; false: prefer the path that keeps clear.
  bool compare = true;
  // ... the two paths planned on two threads at once: the same answer, sooner where a core is
  // free, later where every core is busy (a second thread then waits its turn).
  bool compare_in_parallel = false;
};

class ClearanceCost {
 public:
  // An AStarOptions::extra_step_cost for `grid`: cost_cells * (1 - clearance / width_m) for a
  // cell whose clearance to the nearest blocked cell (probed along the axes and the horizontal
  // diagonals) is below width_m and whose centre lies free_radius_m or more from `start`, 0 for
  // any other. Empty when either parameter is 0. Each cell's cost is computed once per call of
  // this function; `grid` and this object must outlive the returned function, and the next call
  // invalidates it.
  std::function<double(const Eigen::Vector3i&, int64_t)> forGrid(const VoxelGrid& grid,
                                                                 const Eigen::Vector3d& start,
                                                                 const ClearanceCostParams& params);
  // Sizes the per-cell memo for a grid of this many cells ahead of time (as GridAStar::reserve).
  void reserve(int64_t num_cells);

  // The cost of one cell, computed afresh (the function above memoises it).
  static double cellCost(const VoxelGrid& grid, const Eigen::Vector3i& local,
                         const ClearanceCostParams& params);

 private:
  // Per cell: the generation that computed it (high byte), the cost in 1/255 of cost_cells (low).
  std::vector<uint16_t> memo_;
  uint8_t generation_ = 0;
};

}  // namespace mmh::som
