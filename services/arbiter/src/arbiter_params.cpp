#include "mmh/arbiter/arbiter_params.hpp"

#include "mmh/common/config_constraints.hpp"
#include "mmh/common/geofence.hpp"
#include "mmh/common/vehicle_limits.hpp"

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
  // The registry restricts both enums to the names the parsers accept.
  p.policy = parsePolicy(config.getString("arbiter.policy"));
  const VehicleLimits vehicle = loadVehicleLimits(config);
  p.max_vel_mps = vehicle.max_vel_mps;
  p.max_acc_mps2 = vehicle.max_acc_mps2;
  p.planning_horizon_s = config.getDouble("arbiter.planning_horizon_s");
  p.replan_lead_s = config.getDouble("arbiter.replan_lead_s");
  p.answer_deadline_s = config.getDouble("arbiter.answer_deadline_s");
  p.latency_window_s = config.getDouble("arbiter.latency_window_s");
  p.latency_headroom = config.getDouble("arbiter.latency_headroom");
  p.max_answer_deadline_s = config.getDouble("arbiter.max_answer_deadline_s");
  p.max_slowed_answer_deadline_s = config.getDouble("arbiter.max_slowed_answer_deadline_s");
  p.sensor_range_m = config.getDouble("awareness.sensor_range_m");
  p.slowdown_tolerance = config.getDouble("arbiter.slowdown_tolerance");
  p.max_map_age_s = config.getDouble("arbiter.max_map_age_s");
  p.goal_tolerance_m = config.getDouble("arbiter.goal_tolerance_m");
  p.fixed_replan_distance_m = config.getDouble("arbiter.fixed_replan_distance_m");
  p.parallel_modes = parseParallelModes(config.getString("arbiter.parallel_modes"));
  p.score_jerk_weight_s = config.getDouble("arbiter.score_jerk_weight_s");
  p.stale_map_s = config.getDouble("arbiter.stale_map_s");
  p.stop_retry_period_s = config.getDouble("arbiter.stop_retry_period_s");
  p.emergency_horizon_s = config.getDouble("arbiter.emergency_horizon_s");
  p.stale_odometry_s = config.getDouble("arbiter.stale_odometry_s");
  p.start_escape_radius_m = config.getDouble("arbiter.start_escape_radius_m");
  p.inflation_m = config.getDouble("map.inflation_m");
  p.vehicle_radius_m = config.getDouble("vehicle.radius_m");
  p.check_inflation_m = config.getDouble("arbiter.check_inflation_m");
  p.answer_speed_tolerance = config.getDouble("arbiter.answer_limit_tolerance");
  p.max_answer_duration_s = config.getDouble("arbiter.max_answer_duration_s");
  p.defer_far_collisions = config.getBool("arbiter.defer_far_collisions");
  p.collision_margin_s = config.getDouble("arbiter.collision_margin_s");
  p.replan_fraction = config.getDouble("arbiter.replan_fraction");
  p.slow_plan_ratio = config.getDouble("arbiter.slow_plan_ratio");
  p.slow_plan_replan_s = config.getDouble("arbiter.slow_plan_replan_s");
  p.halfway_keep_margin_s = config.getDouble("arbiter.halfway_keep_margin_s");
  p.halfway_keep_min_left_s = config.getDouble("arbiter.halfway_keep_min_left_s");
  p.known_space_margin_m = config.getDouble("arbiter.known_space_margin_m");
  p.known_space_lead_s = config.getDouble("arbiter.known_space_lead_s");
  p.hidden_face_m = config.getDouble("arbiter.hidden_face_m");
  p.hidden_face_reach_m = config.getDouble("arbiter.hidden_face_reach_m");
  p.reference_min_remaining_s = config.getDouble("arbiter.reference_min_remaining_s");
  p.stop_min_speed_mps = config.getDouble("arbiter.stop_min_speed_mps");
  p.stop_decision_margin_s = config.getDouble("arbiter.stop_decision_margin_s");
  p.failed_round_speed_ratio = config.getDouble("arbiter.failed_round_speed_ratio");
  p.backup_stop = config.getBool("arbiter.backup_stop");
  p.braking_speed_mps = config.getDouble("arbiter.braking_speed_mps");
  p.progress_min_step_m = config.getDouble("arbiter.progress_min_step_m");
  p.progress_new_ground_m = config.getDouble("arbiter.progress_new_ground_m");
  p.stuck_after_s = config.getDouble("arbiter.stuck_after_s");
  p.stuck_still_s = config.getDouble("arbiter.stuck_still_s");
  p.stuck_retry_period_s = config.getDouble("arbiter.stuck_retry_period_s");
  p.backoff_min_distance_m = config.getDouble("arbiter.backoff_min_distance_m");
  p.retrace_speed_mps = config.getDouble("arbiter.retrace_speed_mps");
  p.backoff_clearance_m = config.getDouble("arbiter.backoff_clearance_m");
  p.give_up_s = config.getDouble("arbiter.give_up_s");
  p.goal_relocate_radius_m = config.getDouble("arbiter.goal_relocate_radius_m");
  p.unreachable_retry_s = config.getDouble("arbiter.unreachable_retry_s");
  p.start_position_tolerance_m = config.getDouble("arbiter.start_position_tolerance_m");
  p.start_velocity_tolerance_mps = config.getDouble("arbiter.start_velocity_tolerance_mps");
  p.start_acceleration_tolerance_mps2 =
      config.getDouble("arbiter.start_acceleration_tolerance_mps2");
  p.check_step_s = config.getDouble("arbiter.check_step_s");
  p.geofence_tolerance_m = config.getDouble("arbiter.geofence_tolerance_m");
  p.escape_step_s = config.getDouble("arbiter.escape_step_s");
  p.escape_depth_tolerance_m = config.getDouble("arbiter.escape_depth_tolerance_m");
  const Geofence geofence = loadGeofence(config);
  p.geofence_min_m = geofence.min_m;
  p.geofence_max_m = geofence.max_m;
  // Among them: answer_deadline_s <= replan_lead_s, check_inflation_m <= map.inflation_m.
  checkConfigConstraints(config);
  return p;
}

}  // namespace mmh::arbiter
