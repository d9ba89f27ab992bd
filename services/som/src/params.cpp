#include "mmh/som/params.hpp"

namespace mmh::som {
namespace {

// som.* keys are optional (the defaults of params.hpp apply); present ones are range-checked.
double optDouble(const Config& c, const std::string& key, double def, double lo, double hi) {
  return c.has(key) ? c.getDouble(key, lo, hi) : def;
}
int optInt(const Config& c, const std::string& key, int def, int lo, int hi) {
  return c.has(key) ? c.getInt(key, lo, hi) : def;
}

}  // namespace

SomParams loadSomParams(const Config& c) {
  SomParams p;
  p.max_vel_mps = c.getDouble("vehicle.max_vel_mps", 0.1, 50.0);
  p.max_acc_mps2 = c.getDouble("vehicle.max_acc_mps2", 0.1, 50.0);
  p.geofence_min = c.getVector3("geofence.min_m", -1e5, 1e5);
  p.geofence_max = c.getVector3("geofence.max_m", -1e5, 1e5);
  if ((p.geofence_max - p.geofence_min).minCoeff() <= 0.0)
    throw ConfigError(c.source() + ": geofence.max_m must exceed geofence.min_m on every axis");

  p.astar_max_expansions = optInt(c, "som.astar_max_expansions", 200000, 1000, 50000000);
  p.astar_heuristic_weight =
      optDouble(c, "som.astar_heuristic_weight", p.astar_heuristic_weight, 1.0, 10.0);
  p.start_escape_radius_m = optDouble(c, "som.start_escape_radius_m", 0.5, 0.0, 5.0);
  p.start_escape_clearance_m =
      optDouble(c, "som.start_escape_clearance_m", p.start_escape_clearance_m, 0.0, 5.0);

  CorridorParams& k = p.corridor;
  k.box_margin_m = optDouble(c, "som.corridor_box_margin_m", k.box_margin_m, 0.3, 20.0);
  k.box_margin_z_m = optDouble(c, "som.corridor_box_margin_z_m", k.box_margin_z_m, 0.2, 20.0);
  k.early_round_margin_m =
      optDouble(c, "som.corridor_early_round_margin_m", k.early_round_margin_m, 0.0, 20.0);
  k.seed_length_m = optDouble(c, "som.corridor_seed_length_m", k.seed_length_m, 0.2, 50.0);
  k.iterations = optInt(c, "som.corridor_iterations", k.iterations, 1, 10);
  k.overlap_backoff_m =
      optDouble(c, "som.corridor_overlap_backoff_m", k.overlap_backoff_m, 0.0, 5.0);
  k.junction_margin_m =
      optDouble(c, "som.corridor_junction_margin_m", k.junction_margin_m, 0.0, 1.0);
  k.max_polytopes = optInt(c, "som.corridor_max_polytopes", k.max_polytopes, 1, 1000);

  OptimizerParams& o = p.optimizer;
  o.time_weight = optDouble(c, "som.time_weight", o.time_weight, 1e-3, 1e7);
  o.piece_length_m = optDouble(c, "som.piece_length_m", o.piece_length_m, 0.2, 50.0);
  o.samples_per_piece = optInt(c, "som.samples_per_piece", o.samples_per_piece, 2, 128);
  o.weight_corridor = optDouble(c, "som.weight_corridor", o.weight_corridor, 1.0, 1e9);
  o.weight_velocity = optDouble(c, "som.weight_velocity", o.weight_velocity, 1.0, 1e9);
  o.weight_acceleration = optDouble(c, "som.weight_acceleration", o.weight_acceleration, 1.0, 1e9);
  o.penalty_smoothing = optDouble(c, "som.penalty_smoothing", o.penalty_smoothing, 1e-6, 1.0);
  o.max_evaluations = optInt(c, "som.max_evaluations", o.max_evaluations, 10, 100000);
  o.rel_cost_tolerance = optDouble(c, "som.rel_cost_tolerance", o.rel_cost_tolerance, 0.0, 0.1);
  o.lbfgs_memory = optInt(c, "som.lbfgs_memory", o.lbfgs_memory, 1, 64);
  o.first_step = optDouble(c, "som.first_step", o.first_step, 1e-4, 100.0);
  o.limit_margin = optDouble(c, "som.limit_margin", o.limit_margin, 0.0, 0.2);
  o.corridor_margin_m = optDouble(c, "som.corridor_margin_m", o.corridor_margin_m, 0.0, 0.5);
  o.extra_rounds = optInt(c, "som.extra_rounds", o.extra_rounds, 0, 10);
  o.extra_round_evaluations =
      optInt(c, "som.extra_round_evaluations", o.extra_round_evaluations, 1, 100000);
  o.extra_round_weight_factor =
      optDouble(c, "som.extra_round_weight_factor", o.extra_round_weight_factor, 1.0, 1000.0);
  o.extra_round_limit_excess =
      optDouble(c, "som.extra_round_limit_excess", o.extra_round_limit_excess, 0.0, 1.0);
  o.max_repair_stretch = optDouble(c, "som.max_repair_stretch", o.max_repair_stretch, 1.0, 10.0);
  o.repair_tolerance = optDouble(c, "som.repair_tolerance", o.repair_tolerance, 0.0, 0.05);

  VerifyParams& v = p.verify;
  v.limit_tolerance = optDouble(c, "som.verify_limit_tolerance", v.limit_tolerance, 0.0, 0.2);
  v.corridor_tolerance_m =
      optDouble(c, "som.verify_corridor_tolerance_m", v.corridor_tolerance_m, 0.0, 0.5);
  return p;
}

}  // namespace mmh::som
