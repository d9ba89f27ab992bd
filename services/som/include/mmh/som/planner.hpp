// The Standard Optimization Mode pipeline, without LCM: checks of the request, A* on the
// inflated grid, safe flight corridor, MINCO optimisation, independent verification. Reports
// which step failed and how long each step took.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mmh/common/grid_astar.hpp"
#include "mmh/common/plan_debug.hpp"
#include "mmh/common/plan_status.hpp"
#include "mmh/common/trajectory.hpp"
#include "mmh/common/voxel_grid.hpp"
#include "mmh/som/clearance_cost.hpp"
#include "mmh/som/corridor.hpp"
#include "mmh/som/params.hpp"
#include "mmh/som/trajectory_optimizer.hpp"
#include "mmh/som/verification.hpp"

namespace mmh::som {

// Time of one step of a plan() call, microseconds: wall clock, and CPU time of the calling
// thread (what the step costs when the machine is shared).
struct StepTime {
  double wall_us = 0.0;
  double cpu_us = 0.0;
};

struct PlanTimings {
  StepTime checks, astar, corridor, optimize, verify, total;
};

struct PlanOutput {
  PlanStatus status = PlanStatus::kBadInput;
  std::string detail;
  Trajectory trajectory;              // verified; set only with kOk
  std::vector<Eigen::Vector3d> path;  // shortened A* path
  Corridor corridor;
  std::vector<int> piece_polytope;
  double cost_total = 0.0, cost_control = 0.0, cost_time = 0.0, cost_penalty = 0.0;
  int optimizer_evaluations = 0;
  // Plans made again with the check-margin faces, then with those cells fenced whole (the plan
  // before ran through a cell the arbiter's check margin blocks; see Planner::plan).
  int check_margin_retries = 0;
  // Second candidates from a point ahead of a fast start (lead_point.hpp), and how many won.
  int lead_paths = 0;
  int lead_paths_taken = 0;
  // Paths searched again without the clearance cost (clearance_cost.hpp): its search found no
  // path, or no verified answer along it.
  int clearance_fallbacks = 0;
  // Answers along the path that keeps clear chosen over the shortest (clearance.compare).
  int clearance_taken = 0;
  int64_t astar_expansions = 0;
  VerifyReport verify;
  PlanTimings timings;
  bool ok() const { return status == PlanStatus::kOk; }
};

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
  void prepare(const VoxelGrid& grid) {
    astar_.reserve(grid.numCells());
    if (params_.clearance.cost_cells > 0.0) clearance_cost_.reserve(grid.numCells());
  }

 private:
  SomParams params_;  // max_vel_mps: the speed limit of the current plan
  double vehicle_max_vel_mps_;
  GridAStar astar_;
  ClearanceCost clearance_cost_;
  CorridorBuilder corridor_builder_;
  TrajectoryOptimizer optimizer_;
};

// The shortened A* path and the corridor of `out`, for the ground station (som.publish_debug).
PlanDebug debugOf(const PlanOutput& out);

}  // namespace mmh::som
