// The Emergency Avoidance Mode planner (paper Sec. III.C.3, after EGO-Planner): initial guess ->
// uniform cubic B-spline -> rounds of {collision stretches -> A* guide -> {p, v} anchor pairs ->
// L-BFGS} with the weights chosen by the narrow-space test on the guides -> time re-allocation
// while the limits are broken -> exact conversion to polynomial pieces -> independent
// verification. A restart from the guide of all collisions at once when the rounds run out.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "mmh/common/plan_debug.hpp"
#include "mmh/common/plan_status.hpp"
#include "mmh/common/trajectory.hpp"
#include "mmh/common/voxel_grid.hpp"
#include "mmh/eam/bspline_cost.hpp"
#include "mmh/eam/collision_pairs.hpp"
#include "mmh/eam/eam_params.hpp"
#include "mmh/eam/guide_search.hpp"
#include "mmh/eam/uniform_bspline.hpp"

namespace mmh::eam {

struct PlanRequest {
  KinematicState start;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  // Rest of the committed trajectory from the start time (initial guess); may be empty.
  Trajectory reference;
  double max_speed_mps = 0.0;  // fly no faster (speedLimitFor); 0: the vehicle's max_vel_mps
};

struct PlanStats {
  int rounds = 0;       // optimisations run
  int refines = 0;      // time re-allocations
  int restarts = 0;     // restarts from the guide of all collisions
  int evaluations = 0;  // cost evaluations, all rounds
  int astar_calls = 0;
  int64_t astar_expansions = 0;
  int pairs = 0;     // anchor pairs in the end
  int segments = 0;  // knot intervals of the B-spline
  double initial_duration_s = 0.0;
  double max_speed = 0.0, max_acc = 0.0;  // exact maxima of the answer
  // Wall-clock split (us): collision checks of the curve, A*, L-BFGS, final verification.
  double check_us = 0.0, astar_us = 0.0, optimize_us = 0.0, verify_us = 0.0;
};

struct PlanResult {
  bool ok = false;
  PlanStatus reason = PlanStatus::kOk;
  std::string detail;
  bool narrow = false;  // N: the narrow-space weights were selected
  Trajectory trajectory;
  UniformBspline spline;
  CostTerms terms;           // objective at the answer (weights of the last round)
  CostWeights weights;       // lambda1, lambda2 (boosts included), lambda3 of the last round
  double jerk_energy = 0.0;  // of the answer (exact)
  PlanStats stats;
  std::vector<std::vector<Eigen::Vector3d>> guide_paths;  // A* paths used
  PairSet pairs;                                          // anchor pairs per control point
};

class Planner {
 public:
  explicit Planner(const EamParams& params)
      : params_(params), vehicle_max_vel_mps_(params.max_vel_mps), guides_(params) {}
  PlanResult plan(const VoxelGrid& grid, const PlanRequest& request);
  // Allocates what a plan on this grid needs (call when a map of a new size arrives).
  void prepare(const VoxelGrid& grid) { guides_.prepare(grid); }
  const EamParams& params() const { return params_; }
  // Receives one line per round (collisions, pairs, weights, cost) when set; for debugging.
  void setTrace(std::function<void(const std::string&)> trace) { trace_ = std::move(trace); }

 private:
  struct Attempt;
  // One plan with the initial B-spline's knot span knot_span_s.
  PlanResult planWithKnotSpan(const VoxelGrid& grid, const PlanRequest& req, double knot_span_s);
  enum class RoundsOutcome { kCollisionFree, kStillColliding, kNoPath, kOptimizerError };
  // Collision rounds and time re-allocations on attempt.spline until it is collision-free and
  // within the limits, or the rounds run out.
  RoundsOutcome runRounds(const VoxelGrid& grid, const PlanRequest& req, Attempt& attempt,
                          PlanResult& r);
  // The steps of one pass of runRounds, in their order.
  // What a collision-free curve over the limits needs: accept it, re-time it, or reshape it in
  // a feasibility round (whose counters this call advances).
  enum class LimitAction { kAccept, kRetime, kReshape };
  LimitAction limitAction(Attempt& attempt, int last_free);
  // Re-times the curve from before the first of a run of slow-downs by their product.
  void retimeFromBase(const PlanRequest& req, Attempt& attempt, PlanResult& r);
  // While colliding, once per optimisation round: slows the curve down when it is far over the
  // limits. True when it did.
  bool retimeWhileColliding(const PlanRequest& req, Attempt& attempt, PlanResult& r);
  // One rebound round: A* guides around the colliding stretches, their {p, v} pairs, and an
  // optimisation of the freed control points. Returns the outcome that ends the rounds, if any.
  std::optional<RoundsOutcome> reboundRound(const VoxelGrid& grid,
                                            const std::vector<CollisionStretch>& stretches,
                                            bool feasibility_round, int last_free,
                                            const CostSettings& settings, GuideStats& guide_stats,
                                            Attempt& attempt, PlanResult& r);

  EamParams params_;  // max_vel_mps: the speed limit of the current plan
  double vehicle_max_vel_mps_;
  GuideSearch guides_;
  std::function<void(const std::string&)> trace_;
};

// The A* guides, the B-spline's control points and the {p, v} pairs of `result`, for the ground
// station (eam.publish_debug).
PlanDebug debugOf(const PlanResult& result);

// Exact maxima of speed and acceleration of a uniform cubic B-spline (acceleration is piecewise
// linear, so its maximum is at a knot; speed squared is a quartic per interval).
void bsplineMaxima(const UniformBspline& spline, double* max_speed, double* max_acc);

}  // namespace mmh::eam
