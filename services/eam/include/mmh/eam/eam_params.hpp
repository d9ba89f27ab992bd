// Parameters of the Emergency Avoidance Mode (section `eam` of the configuration plus the shared
// vehicle, geofence, map and awareness keys it uses), read and range-checked at start-up.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "mmh/common/config.hpp"

namespace mmh::eam {

// The weights of J = lambda1(N) Js + lambda2(N) Jc + lambda3 Jf (paper eq. 5).
struct CostWeights {
  double smooth = 1.0;       // lambda1
  double collision = 1.0;    // lambda2
  double feasibility = 1.0;  // lambda3
};

struct EamParams {
  // Vehicle limits (vehicle.*) and the box every trajectory must stay in (geofence.*).
  double max_vel_mps = 3.0;
  double max_acc_mps2 = 2.0;
  Eigen::Vector3d geofence_min = Eigen::Vector3d(-30.0, -30.0, 0.3);
  Eigen::Vector3d geofence_max = Eigen::Vector3d(30.0, 30.0, 2.7);
  // The optimiser's walls stand this far inside the geofence: its penalty is soft, and a curve
  // pressed against a wall ends a few millimetres beyond it.
  double geofence_margin_m = 0.05;
  // The excursion beyond the geofence the arbiter accepts (arbiter.geofence_tolerance_m): a start
  // that far out may be answered with a way back in (fenceForStart).
  double arbiter_geofence_tolerance_m = 0.05;
  // Narrow-space test on the A* path (awareness.narrow_probe_dist_m, shared with awareness).
  double narrow_probe_dist_m = 0.8;

  // Uniform knot span of the initial B-spline (s); the actual span divides the initial duration
  // into whole segments and grows when time is re-allocated.
  double knot_span_s = 0.2;
  // When the rounds at knot_span_s end in collision (or the answer fails verification), the plan
  // is made once more with this finer span, whose control points can bend round an obstacle more
  // sharply (0: no second plan, the default; docs/modes/eam.md).
  double fine_knot_span_s = 0.0;
  // lambda1 / lambda2 for open space (N = 0) and narrow space (N = 1), lambda3 for both.
  double lambda_smooth_open = 1.0;
  double lambda_smooth_narrow = 0.2;
  double lambda_collision_open = 2.0e5;
  double lambda_collision_narrow = 1.0e6;
  double lambda_feasibility = 10.0;
  // Clearance asked beyond each anchor plane (s_f of the collision penalty), on top of the
  // inflation the grid already has: it absorbs the curve cutting corners of its control polygon.
  double clearance_m = 0.1;
  // Only control points within this time of a colliding stretch are optimised (EAM is a local
  // re-optimisation; the rest of the trajectory keeps its shape, and the problem stays small
  // and well conditioned).
  double window_margin_s = 2.5;
  // Start the optimisation from the A* guide path on each colliding stretch (control points
  // placed along it) instead of from the colliding guess.
  bool guide_warm_start = true;
  // Colliding stretches closer than this (in time) share one A* search.
  double merge_gap_s = 2.0;
  // Collision-check / pair-generation rounds (the first included) and time re-allocations.
  int max_rebound_rounds = 10;
  int max_refine_rounds = 5;
  // Restarts when the rounds run out with collisions: from the guess again, with one A* guide
  // around all the collisions at once that avoids slots.
  int max_restarts = 1;
  // L-BFGS evaluations per optimisation, and its relative stopping tolerance on the cost.
  int max_iterations = 200;
  double optimizer_ftol_rel = 1e-2;
  // Accepted excess of the exact max speed / acceleration over the limits (the paper accepts a
  // small dynamic violation in an emergency).
  double limit_tolerance_ratio = 0.05;
  // A* budget per guide search.
  int astar_max_expansions = 200000;
  // Weighted A*: a guide need not be the shortest path, and a weight above 1 saves most of the
  // expansions (the slot cost makes the plain octile heuristic weak).
  double astar_heuristic_weight = 1.5;
  // A guide cell is in a slot when inflated obstacles lie within this distance on both sides
  // (along x, y, z or a horizontal diagonal). When the shortest guide threads a slot, A* runs
  // again with this extra cost (in voxels) per step through a slot cell.
  double astar_slot_width_m = 0.3;
  double astar_slot_cost = 10.0;
  // A* first searches the voxel layers the colliding stretch occupies, widened by this, then
  // the whole geofence band.
  double astar_slab_margin_m = 0.0;
  // ... and the box around the stretch's end points widened by this (horizontally).
  double astar_box_margin_m = 3.0;
  // A start inside the inflated margin (not in an occupied cell) may cross it this far: the
  // vehicle has to be able to leave the margin a newly mapped obstacle put it in.
  double start_escape_radius_m = 0.3;
  // ... but only outwards: on the way out no point nearer to the occupied cells than the start,
  // or than this (whichever is less; see mmh::escapeMinDistance).
  double start_escape_clearance_m = 0.28;
  // Within this time of its start an answer cannot leave the way its start state carries it by
  // more than eam.start_forced_deviation_m (1/2 a_max t^2): margin cells met there, which no
  // plan could avoid, are held to the escape distance above instead of refused (0: off).
  double start_forced_s = 0.2;
};

// Throws ConfigError naming the key when a value is missing or out of range.
EamParams loadEamParams(const Config& config);

}  // namespace mmh::eam
