#include "mmh/eam/planner.hpp"
#include "mmh/common/vehicle_limits.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "mmh/common/collision_check.hpp"
#include "mmh/common/geofence.hpp"
#include "mmh/common/narrow_space.hpp"
#include "mmh/common/trajectory_limits.hpp"
#include "mmh/eam/bspline_optimizer.hpp"
#include "mmh/eam/collision_pairs.hpp"
#include "mmh/eam/initial_guess.hpp"
#include "mmh/eam/time_warp.hpp"
#include "mmh/eam/verification.hpp"

namespace mmh::eam {
namespace {

constexpr int kFirstFree = 3;  // Q_0..Q_2 hold the start state
// Re-allocate time when the exact maxima exceed the limits by more than this (rounding only).
constexpr double kRefineAbove = 1.0 + 1e-3;
// Time re-allocation overshoots slightly so that the start region, which does not scale, rarely
// needs a second one.
constexpr double kRefineMargin = 1.01;
// While collisions remain, time is re-allocated only when the limits are broken by more than
// this: the detours need more time than the guess had, and without it the feasibility term
// keeps pulling the curve back into the obstacles.
constexpr double kRefineWhileColliding = 1.1;
// Sample spacing (in voxels) of the collision check: a quarter voxel like the verification,
// and a tenth after the verification found a graze the coarser check missed.
constexpr double kCheckStep = 0.5;
constexpr double kFineCheckStep = 0.1;
// Collision weight multiplier when collisions remain but no new pair could be made.
constexpr double kCollisionBoost = 4.0;
// A collision-free curve whose limits re-timing cannot fix (the excess lies where the start
// state fixes the speed) is reshaped by optimisations with the feasibility weight raised by this
// factor each time, at most this many per attempt.
constexpr double kFeasibilityBoost = 10.0;
constexpr int kMaxFeasibilityRounds = 3;
// An empty reference whose straight guess collides is replaced by a guess along the A* path
// from the start to the target when that path is longer than the straight line by this factor.
constexpr double kPathGuessRatio = 1.2;
// A re-timing stalled when it removed less than this share of the excess ratio.
constexpr double kRefineProgress = 0.5;
// A re-timing slows the curve up to this long (old time) after the last stretch that broke the
// limits, then returns to the old pace - unless that return would end beyond this share of the
// curve, which is then slowed as a whole.
constexpr double kRefineTailS = 0.5;
constexpr double kLocalRefineShare = 0.9;

PlanResult fail(PlanResult r, PlanStatus reason, std::string detail) {
  r.ok = false;
  r.reason = reason;
  r.detail = std::move(detail);
  r.trajectory = Trajectory();
  return r;
}

// The answer's statistics with the effort of another plan of the same request added (its
// rounds, evaluations, searches and times); the answer's own shape (pairs, segments, maxima).
PlanStats withEffortOf(PlanStats answer, const PlanStats& other) {
  answer.rounds += other.rounds;
  answer.refines += other.refines;
  answer.restarts += other.restarts;
  answer.evaluations += other.evaluations;
  answer.astar_calls += other.astar_calls;
  answer.astar_expansions += other.astar_expansions;
  answer.check_us += other.check_us;
  answer.astar_us += other.astar_us;
  answer.optimize_us += other.optimize_us;
  answer.verify_us += other.verify_us;
  return answer;
}

// Ratio by which the knot span must grow so that the maxima fall within the limits.
double limitRatio(const UniformBspline& spline, const EamParams& p) {
  double vmax = 0.0, amax = 0.0;
  bsplineMaxima(spline, &vmax, &amax);
  return std::max(vmax / p.max_vel_mps, std::sqrt(amax / p.max_acc_mps2));
}

// Slower by `ratio`, without a kink at the start, up to old time tau_end (then back to the old
// pace; infinite: the whole rest). A uniform stretch of the curve would also slow its start,
// which the request fixes; re-solving only the first control points then leaves a jump in speed
// there that shows up as a large deceleration (and more stretching). Instead the curve is
// re-timed through a TimeWarp whose first blend is long enough to shed the speed at half of
// a_max (and so is the blend back), and the control points are re-sampled (same count, longer
// knot span). Anchor pairs and the free mask follow their control points to the new times.
// Returns the warp (new time -> old time).
TimeWarp slowDown(UniformBspline& spline, PairSet& pairs, std::vector<char>& free_mask,
                  double ratio, const KinematicState& start, double max_acc_mps2,
                  double tau_end = std::numeric_limits<double>::infinity()) {
  // One slow-down at most triples the duration (more refines may follow): a larger factor asks
  // for a blend the knot span cannot follow.
  const double k = std::clamp(ratio * kRefineMargin, 1.0, 3.0);
  const UniformBspline old = spline;
  const double dt_old = old.knotSpan();
  const double t_old = old.duration();
  const int n = old.numControlPoints();
  const int segments = old.numSegments();
  const double drop = 1.0 - 1.0 / k;
  // Blend time for a speed v: the warp's tangential acceleration peaks at 1.5 |v| drop / T_b.
  auto blendFor = [&](double v) {
    return std::max(2.0 * dt_old * k, 3.0 * v * drop / max_acc_mps2);
  };
  const double blend = blendFor(start.velocity.norm());
  if (!std::isfinite(k) || blend * (1.0 / k + 0.5 * drop) > 0.8 * t_old) {
    // Too short a curve for a blend: the plain stretch (the start kink is small here).
    spline.setKnotSpan(dt_old * k);
    spline.controlPoints().leftCols(3) = UniformBspline::startControlPoints(start, dt_old * k);
    return TimeWarp(k, 0.0);
  }
  TimeWarp warp(k, blend);
  if (std::isfinite(tau_end) && tau_end < t_old) {
    const TimeWarp local(k, blend, tau_end, blendFor(old.evaluate(1, tau_end).norm()));
    if (local.tauRestored() < kLocalRefineShare * t_old) warp = local;
  }
  const double t_new = warp.newDuration(t_old);
  const double dt = t_new / segments;
  Eigen::Matrix3Xd q = old.controlPoints();
  PairSet new_pairs(pairs.size());
  std::vector<char> new_free(free_mask.size(), 0);
  auto old_index = [&](double tau) {
    return std::clamp(static_cast<int>(std::lround(tau / dt_old + 1.0)), 0, n - 1);
  };
  for (int i = 3; i < segments; ++i) {
    const double t = (i - 1) * dt;
    double rate = 0.0, rate_dot = 0.0;
    const double tau = std::min(warp.tau(t, &rate, &rate_dot), t_old);
    const Eigen::Vector3d acc =
        old.evaluate(2, tau) * rate * rate + old.evaluate(1, tau) * rate_dot;
    q.col(i) = old.evaluate(0, tau) - dt * dt / 6.0 * acc;
    const int j = old_index(tau);
    if (j < static_cast<int>(pairs.size())) new_pairs[i] = pairs[j];
    if (j < static_cast<int>(free_mask.size()) && i < static_cast<int>(new_free.size()))
      new_free[i] = free_mask[j];
  }
  for (int i = 0; i < 3 && i < static_cast<int>(new_free.size()); ++i) new_free[i] = free_mask[i];
  q.leftCols(3) = UniformBspline::startControlPoints(start, dt);
  spline = UniformBspline(q, dt);
  pairs = std::move(new_pairs);
  free_mask = std::move(new_free);
  return warp;
}

// Calls f(lo, hi) with the control points lo..hi of every control velocity (two points) or
// control acceleration (three) above the limits.
template <class F>
void forEachLimitExcess(const UniformBspline& spline, const EamParams& p, F&& f) {
  const Eigen::Matrix3Xd& q = spline.controlPoints();
  const double dt = spline.knotSpan();
  for (int i = 0; i + 1 < q.cols(); ++i) {
    if ((q.col(i + 1) - q.col(i)).norm() / dt > p.max_vel_mps * kRefineAbove) f(i, i + 1);
  }
  for (int i = 0; i + 2 < q.cols(); ++i) {
    const double a = (q.col(i + 2) - 2.0 * q.col(i + 1) + q.col(i)).norm() / (dt * dt);
    if (a > p.max_acc_mps2 * kRefineAbove) f(i, i + 2);
  }
}

// Time at which the curve last breaks v_max or a_max, at the end of the knot intervals its
// offending control points shape; 0 when nowhere.
double lastLimitExcessTime(const UniformBspline& spline, const EamParams& p) {
  int last = -1;
  forEachLimitExcess(spline, p, [&](int, int hi) { last = std::max(last, hi); });
  return last < 0 ? 0.0 : std::min(spline.duration(), (last + 1) * spline.knotSpan());
}

// Integral of |jerk|^2 over pieces of degree <= 3 (jerk 6 c3, constant per piece); exact. The
// general routine of Trajectory builds polynomial products and costs far more.
double cubicJerkEnergy(const Trajectory& traj) {
  double e = 0.0;
  for (const Piece& p : traj.pieces()) {
    if (!p.coeffs.rightCols(kMaxPolyOrder - 4).isZero(0.0)) return traj.jerkEnergy();
    e += 36.0 * p.coeffs.col(3).squaredNorm() * p.duration;
  }
  return e;
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

// Stretches closer than gap_s (in time) are merged: they share one A* search, so that their
// detours agree (one side of an obstacle group rather than a slalom through it).
std::vector<CollisionStretch> mergeStretches(const std::vector<CollisionStretch>& stretches,
                                             double gap_s) {
  std::vector<CollisionStretch> groups;
  for (const CollisionStretch& s : stretches) {
    if (!groups.empty() && s.blocked.front().t - groups.back().blocked.back().t < gap_s) {
      CollisionStretch& g = groups.back();
      g.blocked.insert(g.blocked.end(), s.blocked.begin(), s.blocked.end());
      g.after = s.after;
      g.t_after = s.t_after;
    } else {
      groups.push_back(s);
    }
  }
  return groups;
}

}  // namespace

// State of one attempt: the spline being shaped and what the rounds have learnt about it.
struct Planner::Attempt {
  UniformBspline spline;
  PairSet pairs;
  std::vector<char> free_mask;       // control points within window_margin_s of a collision
  double boost = 1.0;                // extra factor on the collision weight
  int round = 0;                     // optimisations run in this attempt
  int refines = 0;                   // time re-allocations in this attempt
  double check_step = 0.0;           // collision check sample spacing (m)
  bool restart = false;              // first round: one guide for all collisions, slots avoided
  double escape_min_distance = 0.0;  // mmh::escapeMinDistance of the start
  // Time re-allocations of a collision-free curve follow one another without an optimisation
  // in between: each is applied to the curve as it was before the first of them, with the
  // product of their ratios, so that their start blends do not stack up (see refineFromBase).
  bool has_refine_base = false;
  UniformBspline refine_base;
  PairSet refine_base_pairs;
  std::vector<char> refine_base_free;
  double refine_total = 1.0;
  TimeWarp refine_warp;         // the base's time at the current curve's times (last re-timing)
  double refine_tau_end = 0.0;  // slowed up to this time of the base, the pace kept after it
  double ratio_before_refine = 1.0;  // limit ratio before the last re-timing
  double feasibility_boost = 1.0;    // extra factor on the feasibility weight
  int feasibility_rounds = 0;
  // A re-timing while colliding was made since the last optimisation: the next step is an
  // optimisation (re-timed again and again, the curve was slowed 3.7 times over, a 29 s answer
  // for 11 m, each slow-down also adding its start blend to the others).
  bool retimed_while_colliding = false;
};

namespace {

// Nothing pushes the free control points vertically: every anchor pair repels horizontally
// (vertical obstacles, the common case) and the points lie between the geofence's walls
// (costSettingsFor), where the walls do not push. The altitude profile of the guess is then kept
// and only x and y are optimised, a third fewer variables (the jerk energy is separable per axis,
// so z stays as smooth as the guess was).
bool horizontalProblem(const PairSet& pairs, const Eigen::Matrix3Xd& q,
                       const std::vector<int>& free_points, const CostSettings& walls) {
  constexpr double kFlat = 1e-3;
  for (int i : free_points) {
    for (const AnchorPair& pair : pairs[i]) {
      if (std::abs(pair.v.z()) > kFlat) return false;
    }
    const double z = q(2, i);
    if (z < walls.box_min.z() || z > walls.box_max.z()) return false;
  }
  return true;
}

// Frees the control points that shape the knot intervals where the control velocities or
// accelerations exceed the limits, and those within `margin` points of them. True if any.
bool freeAroundLimitExcess(const UniformBspline& spline, const EamParams& p, int margin,
                           int first_free, int last_free, std::vector<char>& free_mask) {
  bool any = false;
  forEachLimitExcess(spline, p, [&](int lo, int hi) {
    for (int i = std::max(first_free, lo - margin); i <= std::min(last_free, hi + margin); ++i) {
      free_mask[i] = 1;
      any = true;
    }
  });
  return any;
}

}  // namespace

void bsplineMaxima(const UniformBspline& spline, double* max_speed, double* max_acc) {
  const Eigen::Matrix3Xd& q = spline.controlPoints();
  const double dt = spline.knotSpan();
  double a2 = 0.0, v2 = 0.0;
  for (int i = 0; i + 2 < q.cols(); ++i) {
    a2 = std::max(a2, (q.col(i + 2) - 2.0 * q.col(i + 1) + q.col(i)).squaredNorm());
  }
  // The velocity of interval i is a quadratic B-spline with control points (Q_{k+1} - Q_k)/dt,
  // k = i..i+2, and lies in their convex hull: an interval whose control velocities are all
  // slower than the fastest speed found so far cannot hold the maximum and is skipped.
  std::vector<double> cv2(q.cols() > 1 ? q.cols() - 1 : 0);
  for (int k = 0; k + 1 < q.cols(); ++k) cv2[k] = (q.col(k + 1) - q.col(k)).squaredNorm();
  const double inv_dt2 = 1.0 / (dt * dt);
  for (int i = 0; i + 3 < q.cols(); ++i) {
    const double bound = std::max({cv2[i], cv2[i + 1], cv2[i + 2]}) * inv_dt2;
    if (bound <= v2) continue;
    // v(t) = b0 + b1 t + b2 t^2 on [0, dt]; stationary points of |v|^2 solve v . v' = 0.
    const Eigen::Vector3d b0 = (q.col(i + 2) - q.col(i)) / (2.0 * dt);
    const Eigen::Vector3d b1 = (q.col(i) - 2.0 * q.col(i + 1) + q.col(i + 2)) / (dt * dt);
    const Eigen::Vector3d b2 =
        (-q.col(i) + 3.0 * q.col(i + 1) - 3.0 * q.col(i + 2) + q.col(i + 3)) / (2.0 * dt * dt * dt);
    v2 = maxSquaredQuadraticNorm(b0, b1, b2, dt, v2);
  }
  *max_speed = std::sqrt(v2);
  *max_acc = std::sqrt(a2) / (dt * dt);
}

Planner::RoundsOutcome Planner::runRounds(const VoxelGrid& grid, const PlanRequest& req,
                                          Attempt& at, PlanResult& r) {
  const EamParams& P = params_;
  const int last_free = at.spline.numControlPoints() - 4;
  const CostSettings settings = costSettingsFor(P);
  GuideStats guide_stats;
  RoundsOutcome outcome = RoundsOutcome::kStillColliding;
  for (;;) {
    const std::vector<CollisionStretch> stretches = timed(&r.stats.check_us, [&] {
      return findCollisionStretches(at.spline, grid, P.start_escape_radius_m, at.check_step,
                                    at.escape_min_distance, P.start_forced_s);
    });
    bool feasibility_round = false;
    if (stretches.empty()) {
      const LimitAction action = limitAction(at, last_free);
      if (action == LimitAction::kAccept) {
        outcome = RoundsOutcome::kCollisionFree;
        break;
      }
      if (action == LimitAction::kRetime) {
        retimeFromBase(req, at, r);
        continue;  // check collisions again with the new start
      }
      feasibility_round = true;
    }
    if (at.round >= P.max_rebound_rounds) break;
    if (!feasibility_round && retimeWhileColliding(req, at, r)) continue;
    const std::optional<RoundsOutcome> end =
        reboundRound(grid, stretches, feasibility_round, last_free, settings, guide_stats, at, r);
    if (end) {
      outcome = *end;
      break;
    }
  }
  r.stats.astar_calls += guide_stats.calls;
  r.stats.astar_expansions += guide_stats.expansions;
  r.stats.astar_us += guide_stats.us;
  return outcome;
}

Planner::LimitAction Planner::limitAction(Attempt& at, int last_free) {
  const EamParams& P = params_;
  const double ratio = limitRatio(at.spline, P);
  if (ratio <= kRefineAbove) return LimitAction::kAccept;
  // Re-timing slows the whole curve but keeps the start state, so it cannot remove an excess
  // that the start forces (e.g. a swerve at speed right after it): when it stalls, or may not go
  // on, reshape the curve there with a stronger feasibility term instead.
  const bool stalled =
      at.has_refine_base && ratio > 1.0 + kRefineProgress * (at.ratio_before_refine - 1.0);
  const int margin = static_cast<int>(std::ceil(P.window_margin_s / at.spline.knotSpan()));
  if ((stalled || at.refines >= P.max_refine_rounds) &&
      at.feasibility_rounds < kMaxFeasibilityRounds && at.round < P.max_rebound_rounds &&
      freeAroundLimitExcess(at.spline, P, margin, kFirstFree, last_free, at.free_mask)) {
    ++at.feasibility_rounds;
    at.feasibility_boost *= kFeasibilityBoost;
    if (trace_) trace_("feasibility round: limit ratio " + std::to_string(ratio));
    return LimitAction::kReshape;
  }
  if (at.refines >= P.max_refine_rounds) return LimitAction::kAccept;
  return LimitAction::kRetime;
}

void Planner::retimeFromBase(const PlanRequest& req, Attempt& at, PlanResult& r) {
  const EamParams& P = params_;
  const double ratio = limitRatio(at.spline, P);
  at.ratio_before_refine = ratio;
  const double excess_end_s = lastLimitExcessTime(at.spline, P);
  // Each slow-down sheds speed at the start within a blend sized for its own ratio; applied one
  // after another to the same curve, the blends add their decelerations up (a moving start then
  // ends far over a_max after a few of them). Re-time the curve from before the first of them
  // with the product of the ratios instead: one blend, sized for the total.
  if (!at.has_refine_base) {
    at.has_refine_base = true;
    at.refine_base = at.spline;
    at.refine_base_pairs = at.pairs;
    at.refine_base_free = at.free_mask;
    at.refine_total = 1.0;
    at.refine_warp = TimeWarp();
    at.refine_tau_end = 0.0;
  }
  double rate = 0.0, rate_dot = 0.0;
  at.refine_tau_end = std::max(at.refine_tau_end,
                               at.refine_warp.tau(excess_end_s, &rate, &rate_dot) + kRefineTailS);
  at.refine_total *= ratio;
  at.spline = at.refine_base;
  at.pairs = at.refine_base_pairs;
  at.free_mask = at.refine_base_free;
  at.refine_warp = slowDown(at.spline, at.pairs, at.free_mask, at.refine_total, req.start,
                            P.max_acc_mps2, at.refine_tau_end);
  ++at.refines;
  ++r.stats.refines;
  if (trace_) trace_("refine: knot span x " + std::to_string(at.refine_total * kRefineMargin));
}

bool Planner::retimeWhileColliding(const PlanRequest& req, Attempt& at, PlanResult& r) {
  const EamParams& P = params_;
  if (at.round == 0 || at.retimed_while_colliding || at.refines >= P.max_refine_rounds) {
    return false;
  }
  const double ratio = limitRatio(at.spline, P);
  if (ratio <= kRefineWhileColliding) return false;
  slowDown(at.spline, at.pairs, at.free_mask, ratio, req.start, P.max_acc_mps2);
  at.has_refine_base = false;
  at.retimed_while_colliding = true;
  ++at.refines;
  ++r.stats.refines;
  if (trace_) trace_("refine while colliding: x " + std::to_string(ratio * kRefineMargin));
  return true;
}

std::optional<Planner::RoundsOutcome> Planner::reboundRound(
    const VoxelGrid& grid, const std::vector<CollisionStretch>& stretches, bool feasibility_round,
    int last_free, const CostSettings& settings, GuideStats& guide_stats, Attempt& at,
    PlanResult& r) {
  const EamParams& P = params_;
  // A restart takes one guide around all collisions at once, avoiding slots from the start.
  const std::vector<CollisionStretch> groups =
      mergeStretches(stretches, at.restart && at.round == 0 ? 1e9 : P.merge_gap_s);
  // A restart wants a different, roomier way: slots avoided from the first search and twice
  // as wide, and twice the clearance from the anchor planes.
  const bool avoid_slots = at.restart && at.round == 0;
  const double slot_width = (at.restart ? 2.0 : 1.0) * P.astar_slot_width_m;
  const double clearance = (at.restart ? 2.0 : 1.0) * P.clearance_m;
  int added = 0;
  struct GuideSpan {
    double t0, t1;
    size_t index;  // into r.guide_paths
  };
  std::vector<GuideSpan> round_guides;
  bool no_path = false;
  for (const CollisionStretch& s : groups) {
    const Eigen::Vector3d goal = s.after.cwiseMax(P.geofence_min).cwiseMin(P.geofence_max);
    const Eigen::Vector3d from = s.before.cwiseMax(P.geofence_min).cwiseMin(P.geofence_max);
    double z_lo = std::min(from.z(), goal.z()), z_hi = std::max(from.z(), goal.z());
    for (const CurveSample& b : s.blocked) {
      z_lo = std::min(z_lo, b.point.z());
      z_hi = std::max(z_hi, b.point.z());
    }
    const AStarResult path =
        guides_.find(grid, from, goal, z_lo, z_hi, avoid_slots, slot_width, &guide_stats);
    if (!path.ok()) {
      if (at.round == 0 && !at.restart) {
        no_path = true;
        r.detail = std::string("A* around a colliding stretch: ") + toString(path.status);
        break;
      }
      continue;  // keep the pairs made so far; later rounds or the verification decide
    }
    // N: the narrow-space test of the paper on the guide path. Once narrow, the request keeps
    // the narrow weights.
    if (!r.narrow && isPathNarrow(grid, path.path, P.narrow_probe_dist_m)) r.narrow = true;
    if (at.round == 0 && P.guide_warm_start) {
      warmStartFromGuide(path.path, s.t_before, s.t_after, kFirstFree, last_free, at.spline);
    }
    added +=
        addAnchorPairs(s, path.path, at.spline, grid, kFirstFree, last_free, clearance, at.pairs);
    r.guide_paths.push_back(path.path);
    round_guides.push_back({s.t_before, s.t_after, r.guide_paths.size() - 1});
    const int margin = static_cast<int>(std::ceil(P.window_margin_s / at.spline.knotSpan()));
    const int lo = std::max(kFirstFree, s.blocked.front().segment - margin);
    const int hi = std::min(last_free, s.blocked.back().segment + 3 + margin);
    for (int i = lo; i <= hi; ++i) at.free_mask[i] = 1;
  }
  if (no_path) return RoundsOutcome::kNoPath;
  if (at.round == 0 && P.guide_warm_start && !round_guides.empty()) {
    // The curve through the warm-started control points cuts the corners of the guide, which
    // hugs the obstacles: give those grazes their pairs now (from the same guides) rather
    // than in another round.
    const std::vector<CollisionStretch> grazes = timed(&r.stats.check_us, [&] {
      return findCollisionStretches(at.spline, grid, P.start_escape_radius_m, at.check_step,
                                    at.escape_min_distance, P.start_forced_s);
    });
    for (const CollisionStretch& g : grazes) {
      for (const GuideSpan& span : round_guides) {
        if (g.blocked.back().t < span.t0 || g.blocked.front().t > span.t1) continue;
        added += addAnchorPairs(g, r.guide_paths[span.index], at.spline, grid, kFirstFree,
                                last_free, clearance, at.pairs);
        break;
      }
    }
  }
  if (added == 0 && at.round > 0 && !feasibility_round) at.boost *= kCollisionBoost;
  std::vector<int> free_points;
  for (int i = kFirstFree; i <= last_free; ++i) {
    if (at.free_mask[i]) free_points.push_back(i);
  }
  if (free_points.empty()) return RoundsOutcome::kStillColliding;

  CostWeights w;
  w.smooth = r.narrow ? P.lambda_smooth_narrow : P.lambda_smooth_open;
  w.collision = at.boost * (r.narrow ? P.lambda_collision_narrow : P.lambda_collision_open);
  w.feasibility = at.feasibility_boost * P.lambda_feasibility;
  r.weights = w;
  const BsplineCost cost(settings, w, &at.pairs);
  const bool keep_altitude =
      horizontalProblem(at.pairs, at.spline.controlPoints(), free_points, settings);
  const OptimizeResult opt = timed(&r.stats.optimize_us, [&] {
    return optimizeControlPoints(at.spline, cost, free_points, P.max_iterations,
                                 P.optimizer_ftol_rel, keep_altitude);
  });
  at.has_refine_base = false;  // the curve changed: later re-timings start from it
  at.retimed_while_colliding = false;
  ++at.round;
  ++r.stats.rounds;
  r.stats.evaluations += opt.evaluations;
  if (!opt.ok) {
    r.detail = opt.error;
    return RoundsOutcome::kOptimizerError;
  }
  r.terms = opt.terms;
  if (trace_) {
    trace_("round " + std::to_string(at.round) + ": stretches " + std::to_string(stretches.size()) +
           ", pairs added " + std::to_string(added) + ", dt " +
           std::to_string(at.spline.knotSpan()) + (r.narrow ? ", narrow" : ", open") + ", evals " +
           std::to_string(opt.evaluations) + ", Js " + std::to_string(opt.terms.smooth) + ", Jc " +
           std::to_string(opt.terms.collision) + ", Jf " + std::to_string(opt.terms.feasibility) +
           (keep_altitude ? ", xy" : ", xyz") + " " + opt.error);
  }
  return std::nullopt;
}

PlanResult Planner::plan(const VoxelGrid& grid, const PlanRequest& req) {
  params_.max_vel_mps = speedLimitFor(req.max_speed_mps, vehicle_max_vel_mps_);
  PlanResult coarse = planWithKnotSpan(grid, req, params_.knot_span_s);
  const double fine_span_s = params_.fine_knot_span_s;
  const bool may_retry =
      coarse.reason == PlanStatus::kOptimizer || coarse.reason == PlanStatus::kVerify;
  if (coarse.ok || !may_retry || !(fine_span_s > 0.0) || fine_span_s >= params_.knot_span_s)
    return coarse;
  PlanResult fine = planWithKnotSpan(grid, req, fine_span_s);
  PlanResult& answer = fine.ok ? fine : coarse;
  answer.stats = withEffortOf(answer.stats, fine.ok ? coarse.stats : fine.stats);
  return answer;
}

PlanResult Planner::planWithKnotSpan(const VoxelGrid& grid, const PlanRequest& req,
                                     double knot_span_s) {
  PlanResult r;
  const EamParams& P = params_;
  // --- input checks -----------------------------------------------------------------------
  if (!req.start.position.allFinite() || !req.start.velocity.allFinite() ||
      !req.start.acceleration.allFinite() || !req.target.allFinite())
    return fail(r, PlanStatus::kBadInput, "start state or target is not finite");
  if (!req.reference.empty() && !req.reference.isFinite())
    return fail(r, PlanStatus::kBadInput, "reference trajectory is not finite or has empty pieces");
  if (!grid.valid()) return fail(r, PlanStatus::kNoMap, "no map");
  if (!insideBox(req.target, P.geofence_min, P.geofence_max))
    return fail(r, PlanStatus::kTargetOutOfBounds, "target outside the geofence");
  if ((req.target - req.start.position).norm() < 1e-3 && req.start.velocity.norm() < 1e-3 &&
      req.start.acceleration.norm() < 1e-3)
    return fail(r, PlanStatus::kStartEqualsTarget, "already at rest on the target");
  if (grid.isOccupiedPoint(req.start.position))
    return fail(r, PlanStatus::kStartInObstacle, "start inside an occupied cell");
  if (grid.isBlockedPoint(req.target))
    return fail(r, PlanStatus::kTargetInObstacle, "target inside the inflated obstacles");
  const double tol = 1.0 + P.limit_tolerance_ratio;
  if (req.start.velocity.norm() > tol * P.max_vel_mps ||
      req.start.acceleration.norm() > tol * P.max_acc_mps2)
    return fail(r, PlanStatus::kInfeasibleStart, "start speed or acceleration beyond the limits");

  // --- initial guess ----------------------------------------------------------------------
  const Trajectory guess =
      req.reference.empty() ? straightQuintic(req.start, req.target, P.max_vel_mps, P.max_acc_mps2)
                            : req.reference;
  UniformBspline initial = sampleToBspline(guess, req.start, req.target, knot_span_s);
  const double escape_min_distance =
      escapeMinDistance(grid, req.start.position, P.start_escape_clearance_m);
  if (req.reference.empty()) {
    // The straight guess's duration (and so its number of control points) fits the straight
    // line. When that line is blocked and the way around is much longer (a narrow passage
    // behind the start), the rounds bend too few, too widely spaced control points around the
    // obstacles and every attempt still cuts them. Guess along the A* path instead, with as many
    // control points as its length needs.
    const bool blocked = !timed(&r.stats.check_us, [&] {
                            return findCollisionStretches(initial, grid, P.start_escape_radius_m,
                                                          kCheckStep * grid.resolution(),
                                                          escape_min_distance, P.start_forced_s);
                          }).empty();
    if (blocked) {
      GuideStats gs;
      const double z_lo = std::min(req.start.position.z(), req.target.z());
      const double z_hi = std::max(req.start.position.z(), req.target.z());
      const AStarResult path = guides_.find(grid, req.start.position, req.target, z_lo, z_hi, false,
                                            P.astar_slot_width_m, &gs);
      r.stats.astar_calls += gs.calls;
      r.stats.astar_expansions += gs.expansions;
      r.stats.astar_us += gs.us;
      if (path.ok() &&
          pathLength(path.path) > kPathGuessRatio * (req.target - req.start.position).norm()) {
        initial = sampleAlongPath(shortenPath(grid, path.path), req.start, req.target, knot_span_s,
                                  P.max_vel_mps, P.max_acc_mps2);
        if (trace_)
          trace_("guess along the A* path: " + std::to_string(initial.numSegments()) + " segments");
      }
    }
  }
  r.stats.initial_duration_s = initial.duration();
  r.stats.segments = initial.numSegments();

  // --- attempts: the rounds from the guess, then (when they run out) a restart ------------------
  PlanStatus reason = PlanStatus::kOptimizer;
  std::string detail;
  bool collides = true;  // the last attempt failed on an obstacle (a restart may help)
  for (int attempt = 0; attempt <= P.max_restarts && collides; ++attempt) {
    Attempt at;
    at.spline = initial;
    at.pairs.assign(initial.numControlPoints(), {});
    at.free_mask.assign(initial.numControlPoints(), 0);
    at.check_step = kCheckStep * grid.resolution();
    at.restart = attempt > 0;
    at.escape_min_distance = escape_min_distance;
    r.stats.restarts = attempt;
    r.guide_paths.clear();
    for (;;) {
      const RoundsOutcome outcome = runRounds(grid, req, at, r);
      r.spline = at.spline;
      r.pairs = at.pairs;
      if (outcome == RoundsOutcome::kNoPath) return fail(r, PlanStatus::kNoPath, r.detail);
      if (outcome == RoundsOutcome::kOptimizerError)
        return fail(r, PlanStatus::kOptimizer, r.detail);
      if (outcome == RoundsOutcome::kStillColliding) {
        reason = PlanStatus::kOptimizer;
        collides = true;
        detail = "still in collision after " + std::to_string(r.stats.rounds) + " rounds";
        break;
      }
      // --- exact conversion and independent verification ------------------------------------
      Trajectory traj = at.spline.toTrajectory();
      const Verification v = timed(&r.stats.verify_us, [&] {
        return verifyTrajectory(traj, grid, req.start, req.target, P);
      });
      r.stats.max_speed = v.max_speed;
      r.stats.max_acc = v.max_acc;
      if (v.ok) {
        for (const auto& list : at.pairs) r.stats.pairs += static_cast<int>(list.size());
        if (r.stats.rounds == 0) {  // nothing to avoid: report with the open-space weights
          r.weights =
              CostWeights{P.lambda_smooth_open, P.lambda_collision_open, P.lambda_feasibility};
        }
        // The objective of the answer itself (after any time re-allocation).
        r.terms = BsplineCost(costSettingsFor(P), r.weights, &at.pairs)
                      .evaluate(at.spline.controlPoints(), at.spline.knotSpan(), nullptr);
        r.jerk_energy = cubicJerkEnergy(traj);
        r.trajectory = std::move(traj);
        r.ok = true;
        r.reason = PlanStatus::kOk;
        r.detail.clear();
        return r;
      }
      reason = PlanStatus::kVerify;
      detail = v.why;
      collides = v.collision;
      // The check and the verification sample different points: a curve that grazes a voxel
      // corner may pass one and not the other. Go on with a finer check.
      if (!v.collision || at.check_step <= kFineCheckStep * grid.resolution() ||
          at.round >= P.max_rebound_rounds)
        break;
      at.check_step = kFineCheckStep * grid.resolution();
    }
  }
  return fail(r, reason, detail);
}

PlanDebug debugOf(const PlanResult& result) {
  PlanDebug debug;
  debug.paths = result.guide_paths;
  const Eigen::Matrix3Xd& q = result.spline.controlPoints();
  for (Eigen::Index i = 0; i < q.cols(); ++i) debug.control_points.push_back(q.col(i));
  for (size_t i = 0; i < result.pairs.size() && i < debug.control_points.size(); ++i) {
    for (const AnchorPair& pair : result.pairs[i])
      debug.pairs.push_back({static_cast<int>(i), pair.p, pair.v});
  }
  return debug;
}

}  // namespace mmh::eam
