#include "mmh/som/way_planner.hpp"

#include <string>

#include "mmh/common/collision_check.hpp"
#include "mmh/som/lead_point.hpp"
#include "mmh/som/unknown_near_start.hpp"

namespace mmh::som {

namespace {

// Drops the middle of every straight run of the grid path: shortenPath's line-of-sight tests
// then have far fewer candidates (its cost is quadratic in them), for the same kind of result.
std::vector<Eigen::Vector3d> withoutCollinearPoints(const std::vector<Eigen::Vector3d>& path) {
  if (path.size() <= 2) return path;
  std::vector<Eigen::Vector3d> out{path.front()};
  for (size_t i = 1; i + 1 < path.size(); ++i) {
    const Eigen::Vector3d d0 = path[i] - path[i - 1], d1 = path[i + 1] - path[i];
    if ((d0 - d1).norm() > 1e-9) out.push_back(path[i]);
  }
  out.push_back(path.back());
  return out;
}

using StepCost = std::function<double(const Eigen::Vector3i&, int64_t)>;

// Both extra A* costs (either may be empty: no cost).
StepCost sumOfCosts(StepCost a, StepCost b) {
  if (!a) return b;
  if (!b) return a;
  return [a = std::move(a), b = std::move(b)](const Eigen::Vector3i& local, int64_t index) {
    return a(local, index) + b(local, index);
  };
}

}  // namespace

WayPlanner::WayPlanner(const SomParams& params, GridAStar& astar)
    : params_(params),
      astar_(astar),
      optimizer_(params.optimizer, params.max_vel_mps, params.max_acc_mps2) {}

AStarResult::Status WayPlanner::searchPath(const WayRequest& request, bool keep_clear,
                                           PlanOutput* out) {
  const SomParams& p = params_;
  const VoxelGrid& grid = *request.grid;
  const Eigen::Vector3d& start = request.start.position;
  StepTimer step;
  astar_options_ = AStarOptions();
  astar_options_.max_expansions = p.astar_max_expansions;
  astar_options_.unknown_is_free = true;
  astar_options_.heuristic_weight = p.astar_heuristic_weight;
  astar_options_.min_bound = request.bound_lo;
  astar_options_.max_bound = request.bound_hi;
  astar_options_.start_escape_radius_m = request.start_in_margin ? p.start_escape_radius_m : 0.0;
  astar_options_.start_escape_min_distance_m = request.escape_min_distance;
  const StepCost unknown_cost = unknownNearStartCost(grid, start, p.unknown_near_start);
  // A path that keeps clear leaves the straight line more readily; its shortcuts must then also
  // keep out of the unknown cells near the start that the search paid to avoid, or the first
  // leg cuts through the unseen space beside the vehicle after all.
  astar_options_.extra_step_cost =
      keep_clear ? sumOfCosts(unknown_cost, clearance_cost_.forGrid(grid, start, p.clearance))
                 : unknown_cost;
  keep_out_ = keep_clear ? inUnknownNearStart(grid, start, p.unknown_near_start) : nullptr;
  const AStarResult found = astar_.search(grid, start, request.target, astar_options_);
  out->astar_expansions += found.expansions;
  if (found.ok()) out->path = shortenPath(grid, withoutCollinearPoints(found.path), keep_out_);
  step.addTo(&out->timings.astar);
  return found.status;
}

bool WayPlanner::entersMargin(const WayRequest& request, const PlanOutput& out) const {
  return params_.arbiter_check_inflation_m > params_.corridor.check_inflation_m &&
         entersCheckMargin(out.trajectory, *request.grid, params_.arbiter_check_inflation_m);
}

// With check_inflation_m > 0 the corridor keeps out whole the cells the arbiter's check margin
// blocks (obstacle_points.hpp).
std::optional<PlanStatus> WayPlanner::corridorToVerified(const WayRequest& request,
                                                         double check_inflation_m, bool whole_cells,
                                                         PlanOutput* out) {
  const SomParams& p = params_;
  CorridorParams corridor_params = p.corridor;
  corridor_params.check_inflation_m = check_inflation_m;
  corridor_params.check_whole_cells = whole_cells;
  StepTimer step;
  std::string why;
  const bool corridor_ok = corridor_builder_.build(
      *request.grid, out->path, request.bound_lo, request.bound_hi, escape_, corridor_params,
      &out->corridor, &why, request.start.velocity, p.max_acc_mps2);
  step.addTo(&out->timings.corridor);
  if (!corridor_ok) {
    out->detail = why;
    return PlanStatus::kCorridor;
  }
  step.restart();
  optimizer_.setMaxVel(p.max_vel_mps);
  OptimizerOutput opt;
  const bool opt_ok =
      optimizer_.setup(request.start, request.target, out->corridor) && optimizer_.optimize(&opt);
  step.addTo(&out->timings.optimize);
  out->optimizer_evaluations += opt.evaluations;
  out->cost_total = opt.cost_total;
  out->cost_control = opt.cost_control;
  out->cost_time = opt.cost_time;
  out->cost_penalty = opt.cost_penalty;
  if (!opt_ok) {
    out->detail = opt.message.empty() ? std::string("optimizer failed") : opt.message;
    return PlanStatus::kOptimizer;
  }
  out->trajectory = std::move(opt.trajectory);
  out->piece_polytope = std::move(opt.piece_polytope);
  step.restart();
  out->verify = verifyTrajectory(out->trajectory, request.start, request.target, *request.grid,
                                 out->corridor, out->piece_polytope, p.max_vel_mps, p.max_acc_mps2,
                                 p.verify, request.escape_min_distance);
  step.addTo(&out->timings.verify);
  if (!out->verify.ok) {
    out->detail = out->verify.failure;
    return PlanStatus::kVerify;
  }
  return std::nullopt;
}

// Tried first without the margin's cells (a wider corridor, fewer infeasible answers from fast
// starts), again with them when the verified answer runs through such a cell: the arbiter would
// refuse it, and from the same state SOM would give the same answer every round. Still through
// such a cell: once more with those cells fenced whole (many more obstacle points); that answer
// only if it keeps out of them.
std::optional<PlanStatus> WayPlanner::pathToVerified(const WayRequest& request, PlanOutput* out) {
  const SomParams& p = params_;
  std::optional<PlanStatus> failed =
      corridorToVerified(request, p.corridor.check_inflation_m, false, out);
  if (failed || !entersMargin(request, *out)) return failed;
  ++out->check_margin_retries;
  failed = corridorToVerified(request, p.arbiter_check_inflation_m, false, out);
  if (failed || !entersMargin(request, *out)) return failed;
  PlanOutput faces_only = *out;
  ++out->check_margin_retries;
  if (!corridorToVerified(request, p.arbiter_check_inflation_m, true, out) &&
      !entersMargin(request, *out))
    return std::nullopt;
  *out = withEffortOf(std::move(faces_only), *out);
  return std::nullopt;
}

std::optional<PlanStatus> WayPlanner::planAlongPath(const WayRequest& request, PlanOutput* out) {
  const SomParams& p = params_;
  const KinematicState& start = request.start;
  escape_ = EscapeZone();
  if (request.start_in_margin) {
    escape_.center = start.position;
    escape_.radius = p.start_escape_radius_m;
    escape_.min_distance = request.escape_min_distance;
  }
  std::optional<PlanStatus> failed = pathToVerified(request, out);
  if (request.start_in_margin || out->path.size() < 2 ||
      !turnsAwayFromVelocity(start, out->path[1], p.lead))
    return failed;
  const auto lead =
      leadPoint(*request.grid, start, p.max_acc_mps2, request.bound_lo, request.bound_hi, p.lead);
  if (!lead) return failed;
  StepTimer step;
  const AStarResult ahead = astar_.search(*request.grid, *lead, request.target, astar_options_);
  out->astar_expansions += ahead.expansions;
  step.addTo(&out->timings.astar);
  if (!ahead.ok()) return failed;
  PlanOutput first = *out;
  out->path = {start.position};
  for (const Eigen::Vector3d& q :
       shortenPath(*request.grid, withoutCollinearPoints(ahead.path), keep_out_))
    out->path.push_back(q);
  ++out->lead_paths;
  const std::optional<PlanStatus> failed_ahead = pathToVerified(request, out);
  if (!failed_ahead && (failed || out->trajectory.duration() < first.trajectory.duration())) {
    ++out->lead_paths_taken;
    return std::nullopt;
  }
  *out = withEffortOf(std::move(first), *out);
  return failed;
}

}  // namespace mmh::som
