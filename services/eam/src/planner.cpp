#include "mmh/eam/planner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "mmh/common/narrow_space.hpp"
#include "mmh/common/polynomial.hpp"
#include "mmh/eam/bspline_optimizer.hpp"
#include "mmh/eam/collision_pairs.hpp"
#include "mmh/eam/initial_guess.hpp"
#include "mmh/eam/verification.hpp"

namespace mmh::eam {
namespace {

constexpr int kFirstFree = 3;  // Q_0..Q_2 hold the start state
// Re-allocate time when the exact maxima exceed the limits by more than this (rounding only).
constexpr double kRefineAbove = 1.0 + 1e-3;
// Time re-allocation overshoots slightly so that the start region, which does not scale, rarely
// needs a second one.
constexpr double kRefineMargin = 1.01;
// While collisions remain, time is re-allocated only when the limits are broken by more than this.
constexpr double kRefineWhileColliding = 1.1;
// Collision weight multiplier when collisions remain but no new pair could be made.
constexpr double kCollisionBoost = 4.0;

PlanResult fail(PlanResult r, FailReason reason, std::string detail) {
  r.ok = false;
  r.reason = reason;
  r.detail = std::move(detail);
  r.trajectory = Trajectory();
  return r;
}

bool inBox(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
}

// Ratio by which the knot span must grow so that the maxima fall within the limits.
double limitRatio(const UniformBspline& spline, const EamParams& p) {
  double vmax = 0.0, amax = 0.0;
  bsplineMaxima(spline, &vmax, &amax);
  return std::max(vmax / p.max_vel_mps, std::sqrt(amax / p.max_acc_mps2));
}

// Runs f and adds its wall-clock time (us) to *acc: measurement only, never a decision.
template <class F>
auto timed(double* acc, F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  auto result = f();
  *acc += std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

// Point at arc length s along a polyline.
Eigen::Vector3d pointAt(const std::vector<Eigen::Vector3d>& path, double s) {
  for (size_t k = 0; k + 1 < path.size(); ++k) {
    const double len = (path[k + 1] - path[k]).norm();
    if (s <= len) return path[k] + (path[k + 1] - path[k]) * (len > 0.0 ? s / len : 0.0);
    s -= len;
  }
  return path.back();
}

// Puts the free control points whose knot time lies in (t0, t1) on the guide path, spread by
// arc length in proportion to time: the optimisation then starts from a curve that follows a
// collision-free route instead of having to be pushed out of the obstacles.
void warmStartFromGuide(const std::vector<Eigen::Vector3d>& guide, double t0, double t1,
                        int first_free, int last_free, UniformBspline& spline) {
  if (guide.size() < 2 || t1 <= t0) return;
  const double total = pathLength(guide);
  const double dt = spline.knotSpan();
  for (int i = first_free; i <= last_free; ++i) {
    const double t = (i - 1) * dt;  // Q_i weighs most on the curve at this time
    if (t <= t0 || t >= t1) continue;
    spline.controlPoints().col(i) = pointAt(guide, total * (t - t0) / (t1 - t0));
  }
}

}  // namespace

// Does the cell lie in a slot: inflated obstacles within `reach` voxels on both sides along x, y
// or z, or within `diag_reach` on both sides along a horizontal diagonal?
bool inSlot(const VoxelGrid& grid, const Eigen::Vector3i& c, int reach, int diag_reach) {
  const int axes[5][4] = {{1, 0, 0, reach},
                          {0, 1, 0, reach},
                          {0, 0, 1, reach},
                          {1, 1, 0, diag_reach},
                          {1, -1, 0, diag_reach}};
  for (const auto& a : axes) {
    const Eigen::Vector3i d(a[0], a[1], a[2]);
    bool plus = false, minus = false;
    for (int k = 1; k <= a[3] && !plus; ++k) plus = grid.isBlocked(c + k * d);
    for (int k = 1; k <= a[3] && !minus; ++k) minus = grid.isBlocked(c - k * d);
    if (plus && minus) return true;
  }
  return false;
}

const char* toString(FailReason reason) {
  switch (reason) {
    case FailReason::kNone:
      return "none";
    case FailReason::kBadInput:
      return "bad input";
    case FailReason::kNoMap:
      return "no map";
    case FailReason::kStartInObstacle:
      return "start in obstacle";
    case FailReason::kTargetInObstacle:
      return "target in obstacle";
    case FailReason::kTargetOutOfBounds:
      return "target out of bounds";
    case FailReason::kInfeasibleStart:
      return "infeasible start";
    case FailReason::kStartEqualsTarget:
      return "start equals target";
    case FailReason::kNoPath:
      return "no path";
    case FailReason::kOptimizer:
      return "optimizer";
    case FailReason::kVerify:
      return "verification";
  }
  return "?";
}

AStarResult Planner::findGuide(const VoxelGrid& grid, const Eigen::Vector3d& from,
                               const Eigen::Vector3d& goal, double z_lo, double z_hi,
                               PlanStats* stats) {
  const EamParams& P = params_;
  AStarOptions band;
  band.max_expansions = P.astar_max_expansions;
  band.min_bound = P.geofence_min;
  band.max_bound = P.geofence_max;
  band.start_escape_radius_m = P.start_escape_radius_m;
  // First a slab around the stretch's altitude (a detour around a new obstacle is almost always
  // sideways, and the slab keeps A* from fanning out over every layer), then the whole band.
  AStarOptions slab = band;
  slab.min_bound.z() = std::max(P.geofence_min.z(), z_lo - P.astar_slab_margin_m);
  slab.max_bound.z() = std::min(P.geofence_max.z(), z_hi + P.astar_slab_margin_m);
  auto search = [&](const AStarOptions& o) {
    AStarResult res = timed(&stats->astar_us, [&] { return astar_.search(grid, from, goal, o); });
    ++stats->astar_calls;
    stats->astar_expansions += res.expansions;
    return res;
  };
  bool in_slab = true;
  AStarResult path = search(slab);
  if (!path.ok() && path.status != AStarResult::Status::kOutOfWindow) {
    in_slab = false;
    path = search(band);
  }
  if (!path.ok()) return path;
  // A shortest path threads gaps one or two voxels wide that no smooth curve at speed can
  // follow; if this one does, search again with a cost on slot cells, which takes a wider way
  // when there is one within a few voxels of detour.
  const int reach =
      std::max(1, static_cast<int>(std::lround(P.astar_slot_width_m / grid.resolution())));
  const int diag_reach = std::max(
      1,
      static_cast<int>(std::lround(P.astar_slot_width_m / (std::sqrt(2.0) * grid.resolution()))));
  bool threads_slot = false;
  for (size_t k = 1; k + 1 < path.path.size() && !threads_slot; ++k) {
    threads_slot = inSlot(grid, grid.localIndexOf(path.path[k]), reach, diag_reach);
  }
  if (threads_slot && P.astar_slot_cost > 0.0) {
    if (static_cast<int64_t>(slot_memo_.size()) != grid.numCells())
      slot_memo_.assign(grid.numCells(), 0);
    AStarOptions o = in_slab ? slab : band;
    o.extra_step_cost = [&](const Eigen::Vector3i& c, int64_t idx) {
      int8_t& m = slot_memo_[idx];
      if (m == 0) {
        m = inSlot(grid, c, reach, diag_reach) ? 1 : 2;
        slot_touched_.push_back(idx);
      }
      return m == 1 ? P.astar_slot_cost : 0.0;
    };
    AStarResult wide = search(o);
    for (int64_t idx : slot_touched_) slot_memo_[idx] = 0;
    slot_touched_.clear();
    if (wide.ok()) path = std::move(wide);
  }
  if (in_slab) {
    // Within the slab, the altitudes of the cell centres (a voxel apart) are quantisation, not
    // intent: ramp them between the end points so that they do not tilt the repulsive
    // directions of points the guide passes close to.
    const double total = pathLength(path.path);
    double along = 0.0;
    for (size_t k = 1; k + 1 < path.path.size(); ++k) {
      along += (path.path[k] - path.path[k - 1]).norm();
      path.path[k].z() = from.z() + (goal.z() - from.z()) * (total > 0.0 ? along / total : 0.0);
    }
  }
  return path;
}

void bsplineMaxima(const UniformBspline& spline, double* max_speed, double* max_acc) {
  const Eigen::Matrix3Xd& q = spline.controlPoints();
  const double dt = spline.knotSpan();
  double a2 = 0.0, v2 = 0.0;
  for (int i = 0; i + 2 < q.cols(); ++i) {
    a2 = std::max(a2, (q.col(i + 2) - 2.0 * q.col(i + 1) + q.col(i)).squaredNorm());
  }
  PolyCoeffs d(4);
  for (int i = 0; i + 3 < q.cols(); ++i) {
    // v(t) = b0 + b1 t + b2 t^2 on [0, dt]; stationary points of |v|^2 solve v . v' = 0.
    const Eigen::Vector3d b0 = (q.col(i + 2) - q.col(i)) / (2.0 * dt);
    const Eigen::Vector3d b1 = (q.col(i) - 2.0 * q.col(i + 1) + q.col(i + 2)) / (dt * dt);
    const Eigen::Vector3d b2 =
        (-q.col(i) + 3.0 * q.col(i + 1) - 3.0 * q.col(i + 2) + q.col(i + 3)) / (2.0 * dt * dt * dt);
    auto speed2 = [&](double t) { return (b0 + t * (b1 + t * b2)).squaredNorm(); };
    v2 = std::max({v2, speed2(0.0), speed2(dt)});
    d << b0.dot(b1), b1.dot(b1) + 2.0 * b0.dot(b2), 3.0 * b1.dot(b2), 2.0 * b2.dot(b2);
    for (double t : polyRealRoots(d, 0.0, dt)) v2 = std::max(v2, speed2(t));
  }
  *max_speed = std::sqrt(v2);
  *max_acc = std::sqrt(a2) / (dt * dt);
}

PlanResult Planner::plan(const VoxelGrid& grid, const PlanRequest& req) {
  PlanResult r;
  const EamParams& P = params_;
  // --- input checks -----------------------------------------------------------------------
  if (!req.start.position.allFinite() || !req.start.velocity.allFinite() ||
      !req.start.acceleration.allFinite() || !req.target.allFinite())
    return fail(r, FailReason::kBadInput, "start state or target is not finite");
  if (!req.reference.empty() && !req.reference.isFinite())
    return fail(r, FailReason::kBadInput, "reference trajectory is not finite or has empty pieces");
  if (!grid.valid()) return fail(r, FailReason::kNoMap, "no map");
  if (!inBox(req.target, P.geofence_min, P.geofence_max))
    return fail(r, FailReason::kTargetOutOfBounds, "target outside the geofence");
  if ((req.target - req.start.position).norm() < 1e-3 && req.start.velocity.norm() < 1e-3 &&
      req.start.acceleration.norm() < 1e-3)
    return fail(r, FailReason::kStartEqualsTarget, "already at rest on the target");
  if (grid.isOccupiedPoint(req.start.position))
    return fail(r, FailReason::kStartInObstacle, "start inside an occupied cell");
  if (grid.isBlockedPoint(req.target))
    return fail(r, FailReason::kTargetInObstacle, "target inside the inflated obstacles");
  const double tol = 1.0 + P.limit_tolerance_ratio;
  if (req.start.velocity.norm() > tol * P.max_vel_mps ||
      req.start.acceleration.norm() > tol * P.max_acc_mps2)
    return fail(r, FailReason::kInfeasibleStart, "start speed or acceleration beyond the limits");

  // --- initial guess ----------------------------------------------------------------------
  const Trajectory guess =
      req.reference.empty() ? straightQuintic(req.start, req.target, P.max_vel_mps, P.max_acc_mps2)
                            : req.reference;
  UniformBspline spline = sampleToBspline(guess, req.start, req.target, P.knot_span_s);
  r.stats.initial_duration_s = spline.duration();
  r.stats.segments = spline.numSegments();
  const int last_free = spline.numControlPoints() - 4;

  CostSettings settings;
  settings.max_vel_mps = P.max_vel_mps;
  settings.max_acc_mps2 = P.max_acc_mps2;
  settings.box_min = P.geofence_min;
  settings.box_max = P.geofence_max;
  PairSet pairs(spline.numControlPoints());
  // Control points being optimised: those within window_margin_s of a colliding stretch.
  std::vector<char> free_mask(spline.numControlPoints(), 0);
  std::vector<int> free_points;
  double boost = 1.0;
  auto weights = [&]() {
    CostWeights w;
    w.smooth = r.narrow ? P.lambda_smooth_narrow : P.lambda_smooth_open;
    w.collision = boost * (r.narrow ? P.lambda_collision_narrow : P.lambda_collision_open);
    w.feasibility = P.lambda_feasibility;
    return w;
  };
  // --- rounds: collisions -> pairs -> optimise; when collision-free but beyond the limits,
  // re-allocate time (longer knot span) and check again ---------------------------------------
  bool collision_free = false;
  int round = 0;  // optimisations run
  for (;;) {
    const std::vector<CollisionStretch> stretches = timed(&r.stats.check_us, [&] {
      return findCollisionStretches(spline, grid, P.start_escape_radius_m);
    });
    collision_free = stretches.empty();
    if (collision_free) {
      const double ratio = limitRatio(spline, P);
      if (ratio <= kRefineAbove || r.stats.refines >= P.max_refine_rounds) break;
      // Slower everywhere: the same control points on a longer knot span (the same curve,
      // speeds / ratio, accelerations / ratio^2), except the first three, which must keep
      // reproducing the start state; then check collisions again with the new start.
      spline.setKnotSpan(spline.knotSpan() * ratio * kRefineMargin);
      spline.controlPoints().leftCols(3) =
          UniformBspline::startControlPoints(req.start, spline.knotSpan());
      ++r.stats.refines;
      if (trace_) trace_("refine: knot span x " + std::to_string(ratio * kRefineMargin));
      continue;
    }
    if (round >= P.max_rebound_rounds) break;
    double ratio = limitRatio(spline, P);
    if (round > 0 && ratio > kRefineWhileColliding && r.stats.refines < P.max_refine_rounds) {
      // Far beyond the limits while still colliding: the detours need more time than the
      // guess had; give it now (same re-allocation as below), or the feasibility term keeps
      // pulling the curve back into the obstacles.
      spline.setKnotSpan(spline.knotSpan() * ratio * kRefineMargin);
      spline.controlPoints().leftCols(3) =
          UniformBspline::startControlPoints(req.start, spline.knotSpan());
      ++r.stats.refines;
      if (trace_)
        trace_("refine while colliding: knot span x " + std::to_string(ratio * kRefineMargin));
      continue;
    }
    // Stretches close to each other share one A* search, so that their detours agree (one
    // side of an obstacle group rather than a slalom through it).
    std::vector<CollisionStretch> groups;
    for (const CollisionStretch& s : stretches) {
      if (!groups.empty() && s.blocked.front().t - groups.back().blocked.back().t < P.merge_gap_s) {
        CollisionStretch& g = groups.back();
        g.blocked.insert(g.blocked.end(), s.blocked.begin(), s.blocked.end());
        g.after = s.after;
        g.t_after = s.t_after;
      } else {
        groups.push_back(s);
      }
    }

    int added = 0;
    for (const CollisionStretch& s : groups) {
      const Eigen::Vector3d goal = s.after.cwiseMax(P.geofence_min).cwiseMin(P.geofence_max);
      const Eigen::Vector3d from = s.before.cwiseMax(P.geofence_min).cwiseMin(P.geofence_max);
      double z_lo = std::min(from.z(), goal.z()), z_hi = std::max(from.z(), goal.z());
      for (const CurveSample& b : s.blocked) {
        z_lo = std::min(z_lo, b.point.z());
        z_hi = std::max(z_hi, b.point.z());
      }
      AStarResult path = findGuide(grid, from, goal, z_lo, z_hi, &r.stats);
      if (!path.ok()) {
        if (round == 0)
          return fail(r, FailReason::kNoPath,
                      std::string("A* around a colliding stretch: ") + toString(path.status));
        continue;  // keep the pairs made so far; the verification has the last word
      }
      if (!r.narrow && isPathNarrow(grid, path.path, P.narrow_probe_dist_m)) r.narrow = true;
      added +=
          addAnchorPairs(s, path.path, spline, grid, kFirstFree, last_free, P.clearance_m, pairs);
      if (round == 0 && P.guide_warm_start) {
        warmStartFromGuide(path.path, s.t_before, s.t_after, kFirstFree, last_free, spline);
      }
      r.guide_paths.push_back(path.path);
      const int margin = static_cast<int>(std::ceil(P.window_margin_s / spline.knotSpan()));
      const int lo = std::max(kFirstFree, s.blocked.front().segment - margin);
      const int hi = std::min(last_free, s.blocked.back().segment + 3 + margin);
      for (int i = lo; i <= hi; ++i) free_mask[i] = 1;
    }
    free_points.clear();
    for (int i = kFirstFree; i <= last_free; ++i) {
      if (free_mask[i]) free_points.push_back(i);
    }
    if (added == 0 && round > 0) boost *= kCollisionBoost;

    r.weights = weights();
    BsplineCost cost(settings, r.weights, &pairs);
    if (free_points.empty()) break;  // nothing collides and nothing was ever moved
    const OptimizeResult opt = timed(&r.stats.optimize_us, [&] {
      return optimizeControlPoints(spline, cost, free_points, P.max_iterations,
                                   P.optimizer_ftol_rel);
    });
    ++round;
    ++r.stats.rounds;
    r.stats.evaluations += opt.evaluations;
    if (!opt.ok) return fail(r, FailReason::kOptimizer, opt.error);
    r.terms = opt.terms;
    if (trace_) {
      trace_("round " + std::to_string(round) + ": stretches " + std::to_string(stretches.size()) +
             ", pairs added " + std::to_string(added) + ", limit ratio " + std::to_string(ratio) +
             ", dt " + std::to_string(spline.knotSpan()) + (r.narrow ? ", narrow" : ", open") +
             ", evals " + std::to_string(opt.evaluations) + ", Js " +
             std::to_string(opt.terms.smooth) + ", Jc " + std::to_string(opt.terms.collision) +
             ", Jf " + std::to_string(opt.terms.feasibility) + " " + opt.error);
    }
  }
  for (const auto& list : pairs) r.stats.pairs += static_cast<int>(list.size());
  r.spline = spline;
  r.pairs = pairs;
  if (!collision_free)
    return fail(r, FailReason::kOptimizer,
                "still in collision after " + std::to_string(r.stats.rounds) + " rounds");

  // --- exact conversion and independent verification --------------------------------------
  Trajectory traj = spline.toTrajectory();
  const Verification v = timed(
      &r.stats.verify_us, [&] { return verifyTrajectory(traj, grid, req.start, req.target, P); });
  r.stats.max_speed = v.max_speed;
  r.stats.max_acc = v.max_acc;
  if (!v.ok) return fail(r, FailReason::kVerify, v.why);
  r.jerk_energy = traj.jerkEnergy();
  r.trajectory = std::move(traj);
  r.ok = true;
  return r;
}

}  // namespace mmh::eam
