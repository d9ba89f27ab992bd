#include "mmh/som/planner.hpp"
#include "mmh/common/vehicle_limits.hpp"

#include <future>
#include <optional>
#include <system_error>
#include <utility>

#include "mmh/common/collision_check.hpp"
#include "mmh/common/geofence.hpp"

namespace mmh::som {

namespace {

// Runs `f` when it goes out of scope.
template <class F>
class ScopeExit {
 public:
  explicit ScopeExit(F f) : f_(std::move(f)) {}
  ScopeExit(const ScopeExit&) = delete;
  ScopeExit& operator=(const ScopeExit&) = delete;
  ~ScopeExit() { f_(); }

 private:
  F f_;
};

}  // namespace

Planner::Planner(const SomParams& params)
    : params_(params),
      vehicle_max_vel_mps_(params.max_vel_mps),
      shortest_(params_, astar_),
      clear_(params_, params_.clearance.compare_in_parallel ? second_astar_ : astar_) {}

void Planner::prepare(const VoxelGrid& grid) {
  const ClearanceCostParams& clearance = params_.clearance;
  astar_.reserve(grid.numCells());
  if (clearance.compare && clearance.compare_in_parallel) second_astar_.reserve(grid.numCells());
  // The way that searches with the clearance cost: the second when the two are compared.
  if (clearance.cost_cells > 0.0)
    (clearance.compare ? clear_ : shortest_).prepareClearanceCost(grid);
}

PlanOutput Planner::plan(const VoxelGrid& grid, const KinematicState& start,
                         const Eigen::Vector3d& target, double max_speed_mps) {
  const StepTimer whole;
  params_.max_vel_mps = speedLimitFor(max_speed_mps, vehicle_max_vel_mps_);
  PlanOutput out;
  StepTime other_thread;  // the CPU time of the way planned on another thread
  auto finish = [&](PlanStatus status, const std::string& detail) -> PlanOutput& {
    out.status = status;
    out.detail = detail;
    if (status == PlanStatus::kVerify) out.refused = std::move(out.trajectory);
    if (status != PlanStatus::kOk) out.trajectory = Trajectory();
    whole.addTo(&out.timings.total);
    out.timings.total.cpu_us += other_thread.cpu_us;
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

  WayRequest request;
  request.grid = &grid;
  request.start = start;
  request.target = target;
  request.bound_lo = bound_lo;
  request.bound_hi = bound_hi;
  request.start_in_margin = grid.isBlockedPoint(start.position);
  request.escape_min_distance =
      request.start_in_margin ? escapeMinDistance(grid, start.position, p.start_escape_clearance_m)
                              : 0.0;

  const bool clearance_on = p.clearance.cost_cells > 0.0 && p.clearance.width_m > 0.0;
  const bool compare_clear = clearance_on && p.clearance.compare;
  bool keep_clear = clearance_on && !compare_clear;

  // The comparison's second way: along the path that keeps clear, when that path differs from
  // the shortest (a copy through `shortest_path`, empty when the shortest has none). With
  // clearance.compare_in_parallel on another thread, from the start of the request.
  struct ClearWay {
    PlanOutput out;
    bool planned = false, ok = false;
  };
  std::promise<std::vector<Eigen::Vector3d>> shortest_path;
  std::future<std::vector<Eigen::Vector3d>> shortest_path_known = shortest_path.get_future();
  auto planClearWay = [&] {
    const StepTimer thread_time;
    ClearWay way;
    if (clear_.searchPath(request, true, &way.out) == AStarResult::Status::kFound) {
      const std::vector<Eigen::Vector3d> shortest = shortest_path_known.get();
      if (!shortest.empty() && way.out.path != shortest) {
        way.planned = true;
        way.ok = !clear_.planAlongPath(request, &way.out) && !clear_.entersMargin(request, way.out);
      }
    }
    thread_time.addTo(&way.out.timings.total);
    return way;
  };
  bool in_parallel = compare_clear && p.clearance.compare_in_parallel;
  std::future<ClearWay> clear_way;
  if (in_parallel) {
    try {
      clear_way = std::async(std::launch::async, planClearWay);
    } catch (const std::system_error&) {
      in_parallel = false;  // no thread to be had: the same answer, planned in turn
    }
  }
  bool path_given = false;
  // However plan() ends (an exception included), the other thread is given the path it may wait
  // for and has ended before the state it reads goes.
  const ScopeExit end_clear_way([&] {
    if (!clear_way.valid()) return;
    if (!path_given) shortest_path.set_value({});
    clear_way.wait();
  });
  // Waits for the other thread (it reads `request` and the map) or plans the way here; its
  // effort is added to `out`.
  auto joinClearWay = [&]() -> ClearWay {
    ClearWay way = in_parallel ? clear_way.get() : planClearWay();
    addEffortOf(&out, way.out);
    if (in_parallel) other_thread = way.out.timings.total;
    return way;
  };

  // --- A* ---------------------------------------------------------------------------------
  AStarResult::Status found = shortest_.searchPath(request, keep_clear, &out);
  if (keep_clear &&
      (found == AStarResult::Status::kNoPath || found == AStarResult::Status::kBudgetExceeded)) {
    keep_clear = false;
    ++out.clearance_fallbacks;
    found = shortest_.searchPath(request, false, &out);
  }
  shortest_path.set_value(found == AStarResult::Status::kFound ? out.path
                                                               : std::vector<Eigen::Vector3d>());
  path_given = true;
  if (found != AStarResult::Status::kFound && in_parallel) joinClearWay();
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
  std::optional<PlanStatus> failed = shortest_.planAlongPath(request, &out);
  if (compare_clear) {
    // The cheaper of the two verified answers by the optimiser's measure (energy + time weight
    // x duration); an answer that enters the arbiter's check margin counts as none.
    const bool shortest_ok = !failed && !shortest_.entersMargin(request, out);
    ClearWay way = joinClearWay();
    if (way.planned && way.ok &&
        (!shortest_ok ||
         way.out.cost_control + way.out.cost_time < out.cost_control + out.cost_time)) {
      // Both ways' effort was added to the shortest's output.
      out = withEffortOf(std::move(way.out), out);
      failed = std::nullopt;
      ++out.clearance_taken;
    }
  }
  // The clearance cost is a preference: where its way gives no answer (a fast start may not
  // turn to the wider gap), or one the arbiter would refuse, the shortest way may do better.
  if (keep_clear && (failed || shortest_.entersMargin(request, out))) {
    PlanOutput kept_clear = out;
    ++out.clearance_fallbacks;
    const std::optional<PlanStatus> failed_before = failed;
    if (shortest_.searchPath(request, false, &out) == AStarResult::Status::kFound)
      failed = shortest_.planAlongPath(request, &out);
    if (!failed_before && (failed || shortest_.entersMargin(request, out))) {
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
