// Parameters of the Standard Optimization Mode (the `som` section of the deployment config plus
// the shared vehicle / geofence / map keys), read with ranges so that a bad value stops the
// service at start-up with the key named.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "mmh/common/config.hpp"
#include "mmh/som/clearance_cost.hpp"
#include "mmh/som/lead_point.hpp"
#include "mmh/som/unknown_near_start.hpp"

namespace mmh::som {

struct CorridorParams {
  // Obstacle points are taken from a box around each seed segment, this much larger on every
  // side; it also bounds the polytope.
  double box_margin_m = 1.0;
  double box_margin_z_m = 0.5;  // vertically
  // Longest seed segment (a sub-segment of the shortened A* path) one polytope is grown around.
  double seed_length_m = 3.0;
  // Hyperplane rounds; an inscribed-ellipsoid step runs between two rounds (FIRI).
  int iterations = 2;
  // Rounds before the last look only this far around the seed (0: the whole box).
  double early_round_margin_m = 0.6;
  // The next polytope's seed starts this far back along the path from where the path leaves the
  // current polytope, so that consecutive polytopes overlap by a usable amount.
  double overlap_backoff_m = 0.5;
  // A junction point must be at least this far inside both polytopes it joins.
  double junction_margin_m = 0.1;
  int max_polytopes = 48;
  // Cells whose centres lie within this of an occupied cell are kept out of the polytopes
  // entirely, not only up to their centres (0: off; see Planner::plan) ...
  double check_inflation_m = 0.0;
  // ... by faces this far outside them: just beyond the verification's corridor tolerance, so
  // that a trajectory verified to stay within it of its polytopes cannot touch such a cell.
  double check_face_clearance_m = 0.021;
  // Points only on the faces towards unblocked 6-neighbours (false), or just off every side,
  // edge and corner of such a cell that borders on a cell outside that margin (true; see
  // BlockedMask::build).
  bool check_whole_cells = false;
};

struct OptimizerParams {
  double time_weight = 1000.0;  // rho in J = int |jerk|^2 dt + rho T
  double piece_length_m = 3.0;  // pieces per polytope = ceil(length / piece_length_m)
  int samples_per_piece = 6;    // constraint samples per piece (trapezoid rule)
  double weight_corridor = 1e5;
  double weight_velocity = 1e3;
  double weight_acceleration = 1e3;
  double penalty_smoothing = 1e-2;  // width of the C2 smoothed-L1 penalty near zero
  // The optimiser aims at limits this much (relative) below v_max / a_max, and at polytopes
  // shrunk by corridor_margin_m, so that the small residual of the penalties stays within the
  // verification tolerances.
  double limit_margin = 0.01;
  double corridor_margin_m = 0.03;
  int max_evaluations = 60;
  // If the result still leaves the corridor, or (with a moving start) exceeds the limits by
  // more than extra_round_limit_excess (relative): up to this many further runs, each with the
  // weight of what is violated multiplied by the factor, of this many evaluations each.
  int extra_rounds = 3;
  int extra_round_evaluations = 40;
  double extra_round_weight_factor = 10.0;
  double extra_round_limit_excess = 0.005;
  // Durations are stretched until the exact max speed / acceleration are within this (relative)
  // of the limits.
  double repair_tolerance = 0.002;
  double max_repair_stretch = 4.0;   // at most this total time stretch
  double rel_cost_tolerance = 1e-3;  // stop when the cost improves less than this (relative)
  int lbfgs_memory = 8;
  double first_step = 0.3;  // length of L-BFGS's first (steepest-descent) step in the variables
};

struct VerifyParams {
  double limit_tolerance = 0.01;  // relative tolerance on v_max and a_max (exact maxima)
  double corridor_tolerance_m = 0.02;
  double endpoint_tolerance_m = 1e-3;
};

struct SomParams {
  double max_vel_mps = 3.0;
  double max_acc_mps2 = 2.0;
  Eigen::Vector3d geofence_min = Eigen::Vector3d(-30.0, -30.0, 0.3);
  Eigen::Vector3d geofence_max = Eigen::Vector3d(30.0, 30.0, 2.7);
  int64_t astar_max_expansions = 200000;
  // Weighted A* (>= 1): far fewer expansions; the corridor and the optimiser straighten the path.
  double astar_heuristic_weight = 2.0;
  // When the start lies in the inflated margin (not in an obstacle), cells within this distance
  // of it may be crossed, so that the vehicle can leave the margin it is in.
  double start_escape_radius_m = 0.5;
  // ... but only outwards: no point of the way out nearer to the occupied cells than the start,
  // or than this (whichever is less; mmh::escapeMinDistance).
  double start_escape_clearance_m = 0.28;
  // A* keeps out of unknown space near the start when a way through mapped space is not much
  // longer (unknown_near_start.hpp).
  UnknownNearStartParams unknown_near_start;
  // A* keeps away from the inflated obstacles where a wider way is not much longer
  // (clearance_cost.hpp).
  ClearanceCostParams clearance;
  // The arbiter's check inflation (arbiter.check_inflation_m): an answer that enters a cell it
  // blocks is planned again with such cells kept out of the corridor (0: never).
  double arbiter_check_inflation_m = 0.25;
  // The excursion beyond the geofence the arbiter accepts (arbiter.geofence_tolerance_m): a start
  // that far out plans its way back in (fenceForStart).
  double arbiter_geofence_tolerance_m = 0.05;
  // A fast start whose A* path turns away sharply also tries a path that first goes on ahead
  // (lead_point.hpp); the faster verified trajectory is the answer.
  LeadPointParams lead;
  CorridorParams corridor;
  OptimizerParams optimizer;
  VerifyParams verify;
};

// Reads vehicle.*, geofence.* and som.* (a missing som key takes its default from
// mmh/common/config_registry.hpp; the initialisers above serve code that builds params directly).
SomParams loadSomParams(const Config& config);

}  // namespace mmh::som
