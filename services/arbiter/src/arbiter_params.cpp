#include "mmh/arbiter/arbiter_params.hpp"

namespace mmh::arbiter {

ParallelModes parseParallelModes(const std::string& name) {
  if (name == "none") return ParallelModes::kNone;
  if (name == "collision") return ParallelModes::kCollision;
  if (name == "always") return ParallelModes::kAlways;
  throw ConfigError("unknown value '" + name + "' (expected none, collision or always)");
}

const char* toString(ParallelModes mode) {
  switch (mode) {
    case ParallelModes::kNone:
      return "none";
    case ParallelModes::kCollision:
      return "collision";
    case ParallelModes::kAlways:
      return "always";
  }
  return "?";
}

Policy parsePolicy(const std::string& name) {
  if (name == "mmh") return Policy::kMmh;
  if (name == "mmh-no-lazy") return Policy::kMmhNoLazy;
  if (name == "mmh-no-awareness") return Policy::kMmhNoAwareness;
  if (name == "ego") return Policy::kEgo;
  if (name == "som") return Policy::kSom;
  throw ConfigError("unknown arbiter policy '" + name +
                    "' (allowed: mmh, mmh-no-lazy, mmh-no-awareness, ego, som)");
}

const char* toString(Policy policy) {
  switch (policy) {
    case Policy::kMmh:
      return "mmh";
    case Policy::kMmhNoLazy:
      return "mmh-no-lazy";
    case Policy::kMmhNoAwareness:
      return "mmh-no-awareness";
    case Policy::kEgo:
      return "ego";
    case Policy::kSom:
      return "som";
  }
  return "?";
}

ArbiterParams loadArbiterParams(const Config& config) {
  ArbiterParams p;
  try {
    p.policy = parsePolicy(config.getString("arbiter.policy"));
  } catch (const ConfigError& e) {
    throw ConfigError(config.source() + ": key 'arbiter.policy': " + e.what());
  }
  p.max_vel_mps = config.getDouble("vehicle.max_vel_mps", 0.1, 50.0);
  p.max_acc_mps2 = config.getDouble("vehicle.max_acc_mps2", 0.1, 50.0);
  p.planning_horizon_s = config.getDouble("arbiter.planning_horizon_s", 0.5, 60.0);
  p.replan_lead_s = config.getDouble("arbiter.replan_lead_s", 0.0, 1.0);
  p.answer_deadline_s = config.getDouble("arbiter.answer_deadline_s", 0.001, 2.0);
  if (p.answer_deadline_s > p.replan_lead_s && p.replan_lead_s > 0.0) {
    throw ConfigError(config.source() +
                      ": key 'arbiter.answer_deadline_s' must not exceed arbiter.replan_lead_s "
                      "(an answer must arrive before its trajectory takes effect)");
  }
  p.goal_tolerance_m = config.getDouble("arbiter.goal_tolerance_m", 0.05, 5.0);
  p.fixed_replan_distance_m = config.getDouble("arbiter.fixed_replan_distance_m", 0.1, 50.0);
  try {
    p.parallel_modes = parseParallelModes(config.getString("arbiter.parallel_modes"));
  } catch (const ConfigError& e) {
    throw ConfigError(config.source() + ": key 'arbiter.parallel_modes': " + e.what());
  }
  p.stale_map_s = config.getDouble("arbiter.stale_map_s", 0.05, 60.0);
  p.stop_retry_period_s = config.getDouble("arbiter.stop_retry_period_s", 0.0, 10.0);
  p.emergency_horizon_s = config.getDouble("arbiter.emergency_horizon_s", 0.0, 60.0);
  p.stale_odometry_s = config.getDouble("arbiter.stale_odometry_s", 0.02, 60.0);
  p.start_escape_radius_m = config.getDouble("arbiter.start_escape_radius_m", 0.0, 5.0);
  p.inflation_m = config.getDouble("map.inflation_m", 0.0, 5.0);
  p.check_inflation_m = config.getDouble("arbiter.check_inflation_m", 0.0, 5.0);
  if (p.check_inflation_m > p.inflation_m) {
    throw ConfigError(config.source() +
                      ": key 'arbiter.check_inflation_m' must not exceed map.inflation_m");
  }
  p.answer_speed_tolerance = config.getDouble("arbiter.answer_limit_tolerance", 0.0, 0.5);
  p.max_answer_duration_s = config.getDouble("arbiter.max_answer_duration_s", 1.0, 3600.0);
  p.defer_far_collisions = config.getBool("arbiter.defer_far_collisions");
  p.collision_margin_s = config.getDouble("arbiter.collision_margin_s", 0.0, 30.0);
  p.replan_fraction = config.getDouble("arbiter.replan_fraction", 0.05, 1.0);
  p.reference_min_remaining_s = config.getDouble("arbiter.reference_min_remaining_s", 0.0, 10.0);
  p.stop_min_speed_mps = config.getDouble("arbiter.stop_min_speed_mps", 0.0, 1.0);
  p.braking_speed_mps = config.getDouble("arbiter.braking_speed_mps", 0.0, 1.0);
  p.start_position_tolerance_m = config.getDouble("arbiter.start_position_tolerance_m", 0.0, 0.1);
  p.start_velocity_tolerance_mps =
      config.getDouble("arbiter.start_velocity_tolerance_mps", 0.0, 1.0);
  p.start_acceleration_tolerance_mps2 =
      config.getDouble("arbiter.start_acceleration_tolerance_mps2", 0.0, 5.0);
  p.check_step_s = config.getDouble("arbiter.check_step_s", 0.001, 0.5);
  p.geofence_tolerance_m = config.getDouble("arbiter.geofence_tolerance_m", 0.0, 1.0);
  p.escape_step_s = config.getDouble("arbiter.escape_step_s", 0.001, 0.1);
  p.escape_depth_tolerance_m = config.getDouble("arbiter.escape_depth_tolerance_m", 0.0, 0.2);
  p.geofence_min_m = config.getVector3("geofence.min_m", -1e5, 1e5);
  p.geofence_max_m = config.getVector3("geofence.max_m", -1e5, 1e5);
  if ((p.geofence_max_m.array() <= p.geofence_min_m.array()).any()) {
    throw ConfigError(config.source() + ": key 'geofence.max_m' must exceed geofence.min_m");
  }
  return p;
}

}  // namespace mmh::arbiter
