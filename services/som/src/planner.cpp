#include "mmh/som/planner.hpp"
#include "mmh/common/vehicle_limits.hpp"

#include <chrono>
#include <cmath>
#include <ctime>
#include <functional>
#include <optional>

#include "mmh/common/collision_check.hpp"
#include "mmh/common/geofence.hpp"

namespace mmh::som {

Planner::Planner(const SomParams& params)
    : params_(params),
      vehicle_max_vel_mps_(params.max_vel_mps),
      optimizer_(params.optimizer, params.max_vel_mps, params.max_acc_mps2) {}

namespace {

// Measures one step (wall clock and thread CPU time).
class StepTimer {
 public:
  StepTimer() { restart(); }
  void restart() {
    wall_ = std::chrono::steady_clock::now();
    cpu_ = threadCpuUs();
  }
  // Adds the time since restart() to *out (a step made twice, e.g. a replan, counts both).
  void addTo(StepTime* out) const {
    out->wall_us +=
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - wall_).count();
    out->cpu_us += threadCpuUs() - cpu_;
  }

 private:
  static double threadCpuUs() {
    timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec * 1e6 + ts.tv_nsec * 1e-3;
  }
  std::chrono::steady_clock::time_point wall_;
  double cpu_ = 0.0;
};

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

// An earlier answer taken after later tries: its result with the effort of every try (times,
// expansions, evaluations and the counts of retries and second candidates).
PlanOutput withEffortOf(PlanOutput answer, const PlanOutput& latest) {
  answer.timings = latest.timings;
  answer.astar_expansions = latest.astar_expansions;
  answer.optimizer_evaluations = latest.optimizer_evaluations;
  answer.check_margin_retries = latest.check_margin_retries;
  answer.lead_paths = latest.lead_paths;
  answer.clearance_fallbacks = latest.clearance_fallbacks;
  return answer;
}

}  // namespace

PlanOutput Planner::plan(const VoxelGrid& grid, const KinematicState& start,
                         const Eigen::Vector3d& target, double max_speed_mps) {
  const StepTimer whole;
  params_.max_vel_mps = speedLimitFor(max_speed_mps, vehicle_max_vel_mps_);
  optimizer_.setMaxVel(params_.max_vel_mps);
  PlanOutput out;
  auto finish = [&](PlanStatus status, const std::string& detail) -> PlanOutput& {
    out.status = status;
    out.detail = detail;
    if (status != PlanStatus::kOk) out.trajectory = Trajectory();
    whole.addTo(&out.timings.total);
    return out;
  };
  const SomParams& p = params_;

  // --- checks -----------------------------------------------------------------------------
  if (!start.position.allFinite() || !start.velocity.allFinite() ||
      !start.acceleration.allFinite() || !target.allFinite())
    return finish(PlanStatus::kBadInput, "start state or target is not finite");
  if (!grid.valid()) return finish(PlanStatus::kNoMap, "no map");
  const Geofence fence = fenceForStart(Geofence{p.geofence_min, p.geofence_max}, start.position,
                                       p.arbiter_geofence_tolerance_m);
  const Eigen::Vector3d bound_lo = fence.min_m.cwiseMax(grid.minCorner());
  const Eigen::Vector3d bound_hi = fence.max_m.cwiseMin(grid.maxCorner());
  if (!grid.containsPoint(start.position) || !insideBox(start.position, bound_lo, bound_hi))
    return finish(PlanStatus::kBadInput, "start outside the geofence or the map window");
  if (!grid.containsPoint(target) || !insideBox(target, p.geofence_min, p.geofence_max))
    return finish(PlanStatus::kTargetOutOfBounds, "target outside the geofence or the map window");
  const double tol = 1.0 + p.verify.limit_tolerance;
  if (start.velocity.norm() > p.max_vel_mps * tol ||
      start.acceleration.norm() > p.max_acc_mps2 * tol)
    return finish(PlanStatus::kInfeasibleStart, "start speed or acceleration above the limits");
  if ((target - start.position).norm() < 1e-3 && start.velocity.norm() < 1e-3 &&
      start.acceleration.norm() < 1e-3)
    return finish(PlanStatus::kStartEqualsTarget, "already at rest on the target");
  if (grid.isOccupiedPoint(start.position))
    return finish(PlanStatus::kStartInObstacle, "start lies in an occupied voxel");
  if (grid.isBlockedPoint(target))
    return finish(PlanStatus::kTargetInObstacle, "target lies inside the inflated obstacles");
  whole.addTo(&out.timings.checks);

  // --- A* ---------------------------------------------------------------------------------
  StepTimer step;
  AStarOptions astar_options;
  astar_options.max_expansions = p.astar_max_expansions;
  astar_options.unknown_is_free = true;
  astar_options.heuristic_weight = p.astar_heuristic_weight;
  astar_options.min_bound = bound_lo;
  astar_options.max_bound = bound_hi;
  const bool start_in_margin = grid.isBlockedPoint(start.position);
  astar_options.start_escape_radius_m = start_in_margin ? p.start_escape_radius_m : 0.0;
  const double escape_min_distance =
      start_in_margin ? escapeMinDistance(grid, start.position, p.start_escape_clearance_m) : 0.0;
  astar_options.start_escape_min_distance_m = escape_min_distance;
  const StepCost unknown_cost = unknownNearStartCost(grid, start.position, p.unknown_near_start);
  const StepCost clearance_cost = clearance_cost_.forGrid(grid, start.position, p.clearance);
  // A path that keeps clear leaves the straight line more readily; its shortcuts must then also
  // keep out of the unknown cells near the start that the search paid to avoid, or the first
  // leg cuts through the unseen space beside the vehicle after all.
  const auto unknown_near_start = inUnknownNearStart(grid, start.position, p.unknown_near_start);
  std::function<bool(const Eigen::Vector3d&)> keep_out;
  // The path, with the clearance cost (if on) or without it.
  auto searchPath = [&](bool keep_clear) {
    step.restart();
    astar_options.extra_step_cost =
        keep_clear ? sumOfCosts(unknown_cost, clearance_cost) : unknown_cost;
    keep_out = keep_clear ? unknown_near_start : nullptr;
    const AStarResult found = astar_.search(grid, start.position, target, astar_options);
    out.astar_expansions += found.expansions;
    if (found.ok()) out.path = shortenPath(grid, withoutCollinearPoints(found.path), keep_out);
    step.addTo(&out.timings.astar);
    return found.status;
  };
  const bool compare_clear = static_cast<bool>(clearance_cost) && p.clearance.compare;
  bool keep_clear = static_cast<bool>(clearance_cost) && !compare_clear;
  AStarResult::Status found = searchPath(keep_clear);
  if (keep_clear &&
      (found == AStarResult::Status::kNoPath || found == AStarResult::Status::kBudgetExceeded)) {
    keep_clear = false;
    ++out.clearance_fallbacks;
    found = searchPath(false);
  }
  switch (found) {
    case AStarResult::Status::kFound:
      break;
    case AStarResult::Status::kStartBlocked:
      return finish(PlanStatus::kStartInObstacle, "start is blocked and cannot escape");
    case AStarResult::Status::kGoalBlocked:
      return finish(PlanStatus::kTargetInObstacle, "target is blocked");
    case AStarResult::Status::kOutOfWindow:
      return finish(PlanStatus::kBadInput, "start or target outside the map window");
    case AStarResult::Status::kNoPath:
    case AStarResult::Status::kBudgetExceeded:
      return finish(PlanStatus::kNoPath, std::string("A*: ") + toString(found));
  }

  // --- corridor, optimisation, verification ------------------------------------------------
  EscapeZone escape;
  if (start_in_margin) {
    escape.center = start.position;
    escape.radius = p.start_escape_radius_m;
    escape.min_distance = escape_min_distance;
  }
  // Corridor, optimisation and verification; with check_inflation_m > 0 the corridor keeps out
  // whole the cells the arbiter's check margin blocks (obstacle_points.hpp). Tried first without
  // them (a wider corridor, fewer infeasible answers from fast starts), again with them when the
  // verified answer runs through such a cell: the arbiter would refuse it, and from the same
  // state SOM would give the same answer every round.
  auto corridorToVerified = [&](double check_inflation_m,
                                bool whole_cells = false) -> std::optional<PlanStatus> {
    CorridorParams corridor_params = p.corridor;
    corridor_params.check_inflation_m = check_inflation_m;
    corridor_params.check_whole_cells = whole_cells;
    step.restart();
    std::string why;
    const bool corridor_ok =
        corridor_builder_.build(grid, out.path, bound_lo, bound_hi, escape, corridor_params,
                                &out.corridor, &why, start.velocity, p.max_acc_mps2);
    step.addTo(&out.timings.corridor);
    if (!corridor_ok) {
      out.detail = why;
      return PlanStatus::kCorridor;
    }
    step.restart();
    OptimizerOutput opt;
    const bool opt_ok = optimizer_.setup(start, target, out.corridor) && optimizer_.optimize(&opt);
    step.addTo(&out.timings.optimize);
    out.optimizer_evaluations += opt.evaluations;
    out.cost_total = opt.cost_total;
    out.cost_control = opt.cost_control;
    out.cost_time = opt.cost_time;
    out.cost_penalty = opt.cost_penalty;
    if (!opt_ok) {
      out.detail = opt.message.empty() ? std::string("optimizer failed") : opt.message;
      return PlanStatus::kOptimizer;
    }
    out.trajectory = std::move(opt.trajectory);
    out.piece_polytope = std::move(opt.piece_polytope);
    step.restart();
    out.verify =
        verifyTrajectory(out.trajectory, start, target, grid, out.corridor, out.piece_polytope,
                         p.max_vel_mps, p.max_acc_mps2, p.verify, escape_min_distance);
    step.addTo(&out.timings.verify);
    if (!out.verify.ok) {
      out.detail = out.verify.failure;
      return PlanStatus::kVerify;
    }
    return std::nullopt;
  };
  // Still through such a cell: once more with those cells fenced whole (many more obstacle
  // points); that answer only if it keeps out of them.
  // Whether the answer in `out` runs through a cell of the arbiter's larger check margin.
  auto entersMargin = [&] {
    return p.arbiter_check_inflation_m > p.corridor.check_inflation_m &&
           entersCheckMargin(out.trajectory, grid, p.arbiter_check_inflation_m);
  };
  auto pathToVerified = [&]() -> std::optional<PlanStatus> {
    std::optional<PlanStatus> failed = corridorToVerified(p.corridor.check_inflation_m);
    if (failed || !entersMargin()) return failed;
    ++out.check_margin_retries;
    failed = corridorToVerified(p.arbiter_check_inflation_m);
    if (failed || !entersMargin()) return failed;
    PlanOutput faces_only = out;
    ++out.check_margin_retries;
    if (!corridorToVerified(p.arbiter_check_inflation_m, true) && !entersMargin())
      return std::nullopt;
    out = withEffortOf(std::move(faces_only), out);
    return std::nullopt;
  };
  // Along out.path; and for a fast start whose path turns away sharply: also the path that first
  // goes on ahead; the faster verified trajectory (both end at the target at rest) is the answer.
  auto planAlongPath = [&]() -> std::optional<PlanStatus> {
    std::optional<PlanStatus> failed = pathToVerified();
    if (!start_in_margin && out.path.size() >= 2 &&
        turnsAwayFromVelocity(start, out.path[1], p.lead)) {
      if (const auto lead = leadPoint(grid, start, p.max_acc_mps2, bound_lo, bound_hi, p.lead)) {
        step.restart();
        const AStarResult ahead = astar_.search(grid, *lead, target, astar_options);
        out.astar_expansions += ahead.expansions;
        step.addTo(&out.timings.astar);
        if (ahead.ok()) {
          PlanOutput first = out;
          out.path = {start.position};
          for (const Eigen::Vector3d& q :
               shortenPath(grid, withoutCollinearPoints(ahead.path), keep_out))
            out.path.push_back(q);
          ++out.lead_paths;
          const std::optional<PlanStatus> failed_ahead = pathToVerified();
          if (!failed_ahead &&
              (failed || out.trajectory.duration() < first.trajectory.duration())) {
            failed = std::nullopt;
            ++out.lead_paths_taken;
          } else {
            out = withEffortOf(std::move(first), out);
          }
        }
      }
    }
    return failed;
  };
  std::optional<PlanStatus> failed = planAlongPath();
  if (compare_clear) {
    // The answer along the path that keeps clear, when that path differs; the cheaper of the
    // two verified answers by the optimiser's measure (energy + time weight x duration).
    const bool shortest_ok = !failed && !entersMargin();
    PlanOutput along_shortest = out;
    if (searchPath(true) == AStarResult::Status::kFound && out.path != along_shortest.path) {
      const std::optional<PlanStatus> failed_clear = planAlongPath();
      const bool clear_ok = !failed_clear && !entersMargin();
      const double cost_clear = out.cost_control + out.cost_time;
      const double cost_shortest = along_shortest.cost_control + along_shortest.cost_time;
      if (clear_ok && (!shortest_ok || cost_clear < cost_shortest)) {
        failed = std::nullopt;
        ++out.clearance_taken;
      } else {
        out = withEffortOf(std::move(along_shortest), out);
      }
    }  // else `out` is still the shortest path's answer, with the second search's effort added
  }
  // The clearance cost is a preference: where its way gives no answer (a fast start may not
  // turn to the wider gap), or one the arbiter would refuse, the shortest way may do better.
  if (keep_clear && (failed || entersMargin())) {
    PlanOutput kept_clear = out;
    ++out.clearance_fallbacks;
    const std::optional<PlanStatus> failed_before = failed;
    if (searchPath(false) == AStarResult::Status::kFound) failed = planAlongPath();
    if (!failed_before && (failed || entersMargin())) {
      // Neither keeps out of the margin: the first answer, as without the fallback.
      out = withEffortOf(std::move(kept_clear), out);
      failed = std::nullopt;
    }
  }
  if (failed) return finish(*failed, out.detail);
  return finish(PlanStatus::kOk, "");
}

PlanDebug debugOf(const PlanOutput& out) {
  PlanDebug debug;
  if (!out.path.empty()) debug.paths.push_back(out.path);
  for (const Polytope& poly : out.corridor.polytopes) debug.polytopes.push_back(poly.halfspaces());
  return debug;
}

}  // namespace mmh::som
