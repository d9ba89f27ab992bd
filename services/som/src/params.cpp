#include "mmh/som/params.hpp"

#include "mmh/common/config_constraints.hpp"
#include "mmh/common/geofence.hpp"
#include "mmh/common/vehicle_limits.hpp"

namespace mmh::som {

namespace {
// Check faces lie this much beyond the corridor tolerance (CorridorParams).
constexpr double kCheckFaceBeyondToleranceM = 0.001;
}  // namespace

SomParams loadSomParams(const Config& c) {
  SomParams p;
  const VehicleLimits vehicle = loadVehicleLimits(c);
  p.max_vel_mps = vehicle.max_vel_mps;
  p.max_acc_mps2 = vehicle.max_acc_mps2;
  const Geofence geofence = loadGeofence(c);
  p.geofence_min = geofence.min_m;
  p.geofence_max = geofence.max_m;

  // som.* keys are optional: a missing one takes the registry's default.
  p.astar_max_expansions = c.getInt("som.astar_max_expansions");
  p.astar_heuristic_weight = c.getDouble("som.astar_heuristic_weight");
  p.start_escape_radius_m = c.getDouble("som.start_escape_radius_m");
  p.start_escape_clearance_m = c.getDouble("som.start_escape_clearance_m");
  p.unknown_near_start.cost_cells = c.getDouble("som.unknown_near_cost_cells");
  p.unknown_near_start.radius_m = c.getDouble("som.unknown_near_radius_m");
  p.clearance.cost_cells = c.getDouble("som.clearance_cost_cells");
  p.clearance.width_m = c.getDouble("som.clearance_width_m");
  p.clearance.free_radius_m = c.getDouble("som.clearance_free_radius_m");
  p.clearance.compare = c.getBool("som.clearance_compare");
  p.clearance.compare_in_parallel = c.getBool("som.clearance_compare_parallel");
  p.lead.min_speed_mps = c.getDouble("som.lead_min_speed_mps");
  p.lead.min_turn_deg = c.getDouble("som.lead_min_turn_deg");
  p.lead.reach = c.getDouble("som.lead_reach");

  CorridorParams& k = p.corridor;
  k.box_margin_m = c.getDouble("som.corridor_box_margin_m");
  k.box_margin_z_m = c.getDouble("som.corridor_box_margin_z_m");
  k.early_round_margin_m = c.getDouble("som.corridor_early_round_margin_m");
  k.seed_length_m = c.getDouble("som.corridor_seed_length_m");
  k.iterations = c.getInt("som.corridor_iterations");
  k.overlap_backoff_m = c.getDouble("som.corridor_overlap_backoff_m");
  k.junction_margin_m = c.getDouble("som.corridor_junction_margin_m");
  k.max_polytopes = c.getInt("som.corridor_max_polytopes");
  p.arbiter_check_inflation_m = c.getDouble("arbiter.check_inflation_m");
  p.arbiter_geofence_tolerance_m = c.getDouble("arbiter.geofence_tolerance_m");

  OptimizerParams& o = p.optimizer;
  o.time_weight = c.getDouble("som.time_weight");
  o.piece_length_m = c.getDouble("som.piece_length_m");
  o.samples_per_piece = c.getInt("som.samples_per_piece");
  o.weight_corridor = c.getDouble("som.weight_corridor");
  o.weight_velocity = c.getDouble("som.weight_velocity");
  o.weight_acceleration = c.getDouble("som.weight_acceleration");
  o.penalty_smoothing = c.getDouble("som.penalty_smoothing");
  o.max_evaluations = c.getInt("som.max_evaluations");
  o.rel_cost_tolerance = c.getDouble("som.rel_cost_tolerance");
  o.lbfgs_memory = c.getInt("som.lbfgs_memory");
  o.first_step = c.getDouble("som.first_step");
  o.limit_margin = c.getDouble("som.limit_margin");
  o.corridor_margin_m = c.getDouble("som.corridor_margin_m");
  o.extra_rounds = c.getInt("som.extra_rounds");
  o.extra_round_evaluations = c.getInt("som.extra_round_evaluations");
  o.extra_round_weight_factor = c.getDouble("som.extra_round_weight_factor");
  o.extra_round_limit_excess = c.getDouble("som.extra_round_limit_excess");
  o.max_repair_stretch = c.getDouble("som.max_repair_stretch");
  o.repair_tolerance = c.getDouble("som.repair_tolerance");

  VerifyParams& v = p.verify;
  v.limit_tolerance = c.getDouble("som.verify_limit_tolerance");
  v.corridor_tolerance_m = c.getDouble("som.verify_corridor_tolerance_m");
  k.check_face_clearance_m = v.corridor_tolerance_m + kCheckFaceBeyondToleranceM;
  checkConfigConstraints(c);
  return p;
}

}  // namespace mmh::som
