#include "mmh/eam/eam_params.hpp"

#include <cmath>

#include "mmh/common/config_constraints.hpp"
#include "mmh/common/geofence.hpp"
#include "mmh/common/vehicle_limits.hpp"

namespace mmh::eam {

EamParams loadEamParams(const Config& config) {
  EamParams p;
  const VehicleLimits vehicle = loadVehicleLimits(config);
  p.max_vel_mps = vehicle.max_vel_mps;
  p.max_acc_mps2 = vehicle.max_acc_mps2;
  const Geofence geofence = loadGeofence(config);
  p.geofence_min = geofence.min_m;
  p.geofence_max = geofence.max_m;
  p.narrow_probe_dist_m = config.getDouble("awareness.narrow_probe_dist_m");

  p.knot_span_s = config.getDouble("eam.knot_span_s");
  p.fine_knot_span_s = config.getDouble("eam.fine_knot_span_s");
  p.lambda_smooth_open = config.getDouble("eam.lambda_smooth_open");
  p.lambda_smooth_narrow = config.getDouble("eam.lambda_smooth_narrow");
  p.lambda_collision_open = config.getDouble("eam.lambda_collision_open");
  p.lambda_collision_narrow = config.getDouble("eam.lambda_collision_narrow");
  p.lambda_feasibility = config.getDouble("eam.lambda_feasibility");
  p.clearance_m = config.getDouble("eam.clearance_m");
  p.geofence_margin_m = config.getDouble("eam.geofence_margin_m");
  p.arbiter_geofence_tolerance_m = config.getDouble("arbiter.geofence_tolerance_m");
  p.window_margin_s = config.getDouble("eam.window_margin_s");
  p.guide_warm_start = config.getBool("eam.guide_warm_start");
  p.merge_gap_s = config.getDouble("eam.merge_gap_s");
  p.max_rebound_rounds = config.getInt("eam.max_rebound_rounds");
  p.max_refine_rounds = config.getInt("eam.max_refine_rounds");
  p.max_restarts = config.getInt("eam.max_restarts");
  p.max_iterations = config.getInt("eam.max_iterations");
  p.optimizer_ftol_rel = config.getDouble("eam.optimizer_ftol_rel");
  p.limit_tolerance_ratio = config.getDouble("eam.limit_tolerance_ratio");
  p.astar_max_expansions = config.getInt("eam.astar_max_expansions");
  p.astar_slot_width_m = config.getDouble("eam.astar_slot_width_m");
  p.astar_slot_cost = config.getDouble("eam.astar_slot_cost");
  p.astar_heuristic_weight = config.getDouble("eam.astar_heuristic_weight");
  p.astar_box_margin_m = config.getDouble("eam.astar_box_margin_m");
  p.astar_slab_margin_m = config.getDouble("eam.astar_slab_margin_m");
  p.start_escape_radius_m = config.getDouble("eam.start_escape_radius_m");
  p.start_escape_clearance_m = config.getDouble("eam.start_escape_clearance_m");
  p.start_forced_s =
      std::sqrt(2.0 * config.getDouble("eam.start_forced_deviation_m") / p.max_acc_mps2);
  checkConfigConstraints(config);
  return p;
}

}  // namespace mmh::eam
