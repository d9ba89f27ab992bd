// The Standard Optimization Mode pipeline, without LCM: checks of the request, A* on the
// inflated grid, safe flight corridor, MINCO optimisation, independent verification. Reports
// which step failed and how long each step took.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mmh/common/grid_astar.hpp"
#include "mmh/common/plan_debug.hpp"
#include "mmh/common/trajectory.hpp"
#include "mmh/common/voxel_grid.hpp"
#include "mmh/som/params.hpp"
#include "mmh/som/plan_output.hpp"
#include "mmh/som/way_planner.hpp"

namespace mmh::som {

class Planner {
 public:
  explicit Planner(const SomParams& params);
  const SomParams& params() const { return params_; }

  // Trajectory from `start` (any state within the limits) to `target` at rest on `grid`, whose
  // inflation radius is the planning margin, no faster than max_speed_mps (speedLimitFor; 0: the
  // vehicle's max_vel_mps).
  PlanOutput plan(const VoxelGrid& grid, const KinematicState& start, const Eigen::Vector3d& target,
                  double max_speed_mps = 0.0);
  // Sizes the per-cell search arrays for this grid's window (call when a map arrives; cheap
  // unless the window size changed) so that plan() does not pay for it.
  void prepare(const VoxelGrid& grid);

 private:
  SomParams params_;  // max_vel_mps: the speed limit of the current plan
  double vehicle_max_vel_mps_;
  // A*'s per-cell search state (tens of MB for a large window): one, shared by both ways when
  // they are planned in turn; a second for the way on its own thread.
  GridAStar astar_;
  GridAStar second_astar_;
  // The shortest path's way (and the only one without the comparison), and the way along the
  // path that keeps clear, which clearance.compare_in_parallel plans on a thread of its own.
  WayPlanner shortest_;
  WayPlanner clear_;
};

// The shortened A* path and the corridor of `out`, for the ground station (som.publish_debug).
PlanDebug debugOf(const PlanOutput& out);

}  // namespace mmh::som
