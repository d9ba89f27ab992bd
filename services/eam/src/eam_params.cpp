#include "mmh/eam/eam_params.hpp"

namespace mmh::eam {

EamParams loadEamParams(const Config& config) {
  EamParams p;
  p.max_vel_mps = config.getDouble("vehicle.max_vel_mps", 0.1, 50.0);
  p.max_acc_mps2 = config.getDouble("vehicle.max_acc_mps2", 0.1, 50.0);
  p.geofence_min = config.getVector3("geofence.min_m", -1e5, 1e5);
  p.geofence_max = config.getVector3("geofence.max_m", -1e5, 1e5);
  if ((p.geofence_max.array() <= p.geofence_min.array()).any())
    throw ConfigError(config.source() + ": key 'geofence.max_m' must exceed 'geofence.min_m'");
  p.narrow_probe_dist_m = config.getDouble("awareness.narrow_probe_dist_m", 0.05, 10.0);

  p.knot_span_s = config.getDouble("eam.knot_span_s", 0.02, 2.0);
  p.lambda_smooth_open = config.getDouble("eam.lambda_smooth_open", 1e-9, 1e9);
  p.lambda_smooth_narrow = config.getDouble("eam.lambda_smooth_narrow", 1e-9, 1e9);
  p.lambda_collision_open = config.getDouble("eam.lambda_collision_open", 1e-9, 1e12);
  p.lambda_collision_narrow = config.getDouble("eam.lambda_collision_narrow", 1e-9, 1e12);
  p.lambda_feasibility = config.getDouble("eam.lambda_feasibility", 0.0, 1e12);
  p.clearance_m = config.getDouble("eam.clearance_m", 0.0, 2.0);
  p.window_margin_s = config.getDouble("eam.window_margin_s", 0.0, 100.0);
  p.guide_warm_start = config.getBool("eam.guide_warm_start");
  p.merge_gap_s = config.getDouble("eam.merge_gap_s", 0.0, 100.0);
  p.max_rebound_rounds = config.getInt("eam.max_rebound_rounds", 1, 50);
  p.max_refine_rounds = config.getInt("eam.max_refine_rounds", 0, 20);
  p.max_restarts = config.getInt("eam.max_restarts", 0, 10);
  p.max_iterations = config.getInt("eam.max_iterations", 10, 100000);
  p.optimizer_ftol_rel = config.getDouble("eam.optimizer_ftol_rel", 1e-12, 0.5);
  p.limit_tolerance_ratio = config.getDouble("eam.limit_tolerance_ratio", 0.0, 0.5);
  p.astar_max_expansions = config.getInt("eam.astar_max_expansions", 1000, 100000000);
  p.astar_slot_width_m = config.getDouble("eam.astar_slot_width_m", 0.0, 5.0);
  p.astar_slot_cost = config.getDouble("eam.astar_slot_cost", 0.0, 1000.0);
  p.astar_heuristic_weight = config.getDouble("eam.astar_heuristic_weight", 1.0, 10.0);
  p.astar_box_margin_m = config.getDouble("eam.astar_box_margin_m", 0.1, 1000.0);
  p.astar_slab_margin_m = config.getDouble("eam.astar_slab_margin_m", 0.0, 100.0);
  p.start_escape_radius_m = config.getDouble("eam.start_escape_radius_m", 0.0, 2.0);
  p.start_escape_clearance_m = config.getDouble("eam.start_escape_clearance_m", 0.0, 2.0);
  return p;
}

}  // namespace mmh::eam
