// One way of answering a SOM request: A* from the start to the target (the shortest path, or the
// path that keeps clear of the obstacles), then the safe flight corridor, the optimisation and
// the verification along that path, with their retries. The planner owns two, so that the two
// paths of its comparison can be planned at the same time: each has its own corridor and
// optimiser state (and then its own A* search state), and only reads the map.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>

#include "mmh/common/grid_astar.hpp"
#include "mmh/common/plan_status.hpp"
#include "mmh/common/trajectory.hpp"
#include "mmh/common/voxel_grid.hpp"
#include "mmh/som/clearance_cost.hpp"
#include "mmh/som/corridor.hpp"
#include "mmh/som/params.hpp"
#include "mmh/som/plan_output.hpp"
#include "mmh/som/trajectory_optimizer.hpp"

namespace mmh::som {

// A request that passed the planner's checks, and what every way of answering it shares.
struct WayRequest {
  const VoxelGrid* grid = nullptr;
  KinematicState start;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  Eigen::Vector3d bound_lo = Eigen::Vector3d::Zero(), bound_hi = Eigen::Vector3d::Zero();
  // The start lies in the inflated margin: cells near it may be crossed, outwards only.
  bool start_in_margin = false;
  double escape_min_distance = 0.0;
};

class WayPlanner {
 public:
  // `params` and `astar` must outlive this object; params.max_vel_mps is read at every call (the
  // speed limit of the current request). Two WayPlanners may share one A* when they never search
  // at the same time.
  WayPlanner(const SomParams& params, GridAStar& astar);

  // Sizes the clearance cost's per-cell memo for this grid's window (cheap unless it changed).
  void prepareClearanceCost(const VoxelGrid& grid) { clearance_cost_.reserve(grid.numCells()); }

  // Searches the path (with the clearance cost or without) into out->path when found, adding the
  // search's effort to *out.
  AStarResult::Status searchPath(const WayRequest& request, bool keep_clear, PlanOutput* out);

  // Corridor, optimisation and verification along out->path, planned again off the arbiter's
  // check margin when the answer enters it; for a fast start whose path turns away sharply also
  // along the path that first goes on ahead, the faster verified answer kept. Uses the search
  // settings of the last searchPath(). The failed step, or nothing when *out holds an answer.
  std::optional<PlanStatus> planAlongPath(const WayRequest& request, PlanOutput* out);

  // Whether the answer in `out` runs through a cell of the arbiter's larger check margin.
  bool entersMargin(const WayRequest& request, const PlanOutput& out) const;

 private:
  std::optional<PlanStatus> pathToVerified(const WayRequest& request, PlanOutput* out);
  std::optional<PlanStatus> corridorToVerified(const WayRequest& request, double check_inflation_m,
                                               bool whole_cells, PlanOutput* out);

  const SomParams& params_;
  GridAStar& astar_;
  ClearanceCost clearance_cost_;
  CorridorBuilder corridor_builder_;
  TrajectoryOptimizer optimizer_;
  // Set by searchPath: the search's options and the unknown cells its shortcuts keep out of.
  AStarOptions astar_options_;
  std::function<bool(const Eigen::Vector3d&)> keep_out_;
  EscapeZone escape_;  // of the start, set by planAlongPath
};

}  // namespace mmh::som
