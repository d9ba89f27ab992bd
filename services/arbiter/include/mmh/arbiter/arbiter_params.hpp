// Parameters of the mode arbiter and the replanning policy (which baseline or ablation runs).
#pragma once

#include <Eigen/Core>
#include <string>

#include "mmh/common/config.hpp"

namespace mmh::arbiter {

// How the arbiter chooses modes and when it replans: the full method, its ablations, and the
// single-mode baselines of the benchmark.
enum class Policy {
  kMmh,             // awareness picks FPM/SOM, EAM on collision or SOM failure, lazy replanning
  kMmhNoLazy,       // as kMmh, but replans every fixed_replan_distance_m of progress
  kMmhNoAwareness,  // as kMmh, but always SOM first (FPM never used)
  kEgo,             // EAM alone, replans every fixed_replan_distance_m and on collision
  kSom,             // SOM alone, same fixed replanning
};

// When several modes are asked at once (the best verified answer is committed).
enum class ParallelModes {
  kNone,       // one mode at a time: SOM, EAM only once SOM failed
  kCollision,  // EAM and SOM together on a collision; otherwise one at a time
  kAlways,     // SOM and EAM together wherever S is false, and on a collision
};

ParallelModes parseParallelModes(const std::string& name);  // throws ConfigError when unknown
const char* toString(ParallelModes mode);

Policy parsePolicy(const std::string& name);  // throws ConfigError on an unknown name
const char* toString(Policy policy);

struct ArbiterParams {
  Policy policy = Policy::kMmh;
  double max_vel_mps = 3.0;
  double max_acc_mps2 = 2.0;
  double planning_horizon_s = 5.0;  // local target: at most max_vel * horizon away
  double replan_lead_s = 0.05;      // a new trajectory takes effect this long after the request
  double answer_deadline_s = 0.04;  // answers later than this after the request are ignored
  // Latency budget (replan_rules.hpp, latencyBudget): observed answer latencies (p99 over the
  // last latency_window_s per mode) times latency_headroom may lengthen the deadline up to
  // max_answer_deadline_s; LOCAL_MAP older than max_map_age_s (p99) on arrival is degraded.
  double latency_window_s = 10.0;
  double latency_headroom = 1.5;
  double max_answer_deadline_s = 0.2;
  // Past max_answer_deadline_s the deadline grows up to this and the speed is lowered so that,
  // after the longer reaction, the vehicle still stops within sensor_range_m.
  double max_slowed_answer_deadline_s = 1.0;
  double sensor_range_m = 4.5;  // awareness.sensor_range_m
  // A committed trajectory faster than the lowered limit by more than this fraction is slowed.
  double slowdown_tolerance = 0.05;
  double max_map_age_s = 0.25;
  double goal_tolerance_m = 0.3;
  double fixed_replan_distance_m = 1.5;  // baselines: replan after this much progress
  // Lazy rule (1): replan once this share of the committed trajectory's duration has passed
  // (the paper's halfway point).
  double replan_fraction = 0.5;
  // A trajectory that ends at the goal is not replanned at its halfway point, unless it takes
  // longer than this x the rest-to-rest bound of its straight length (a crawl out of a tight
  // spot would otherwise be flown to the end).
  double slow_plan_ratio = 2.0;
  // ... and any such crawl is replanned no later than this after it was committed.
  double slow_plan_replan_s = 1.0;
  // A halfway replan whose answer would reach the goal more than halfway_keep_margin_s later
  // than the committed trajectory (answerScore of both) keeps the committed one while more than
  // halfway_keep_min_left_s of it is left, and replans again halfway through the rest.
  double halfway_keep_margin_s = 0.5;
  double halfway_keep_min_left_s = 2.0;
  // An answer must stay in mapped space within its stopping distance plus this margin, counted
  // from the point it reaches known_space_lead_s (plus the replan lead) after its start.
  double known_space_margin_m = 0.3;
  double known_space_lead_s = 0.1;
  // Beside the centre line, within vehicle_radius_m, unknown cells this close to an occupied cell
  // count as unmapped space too: a mapped obstacle's unseen side (0: the centre line only).
  double hidden_face_m = 0.3;
  double hidden_face_reach_m = 0.5;  // ... within this much path (farther, the sensor sees them)
  ParallelModes parallel_modes = ParallelModes::kNone;
  // answerScore: seconds added per m^2/s^5 of an answer's jerk energy (0: time to the goal only).
  double score_jerk_weight_s = 0.0;
  double inflation_m = 0.3;              // the planners' map inflation (local target clearance)
  double vehicle_radius_m = 0.15;        // airframe: a stop that brings it into an occupied cell
                                         // is the last one to choose
  double check_inflation_m = 0.25;       // inflation of the arbiter's own collision checks; a bit
                                         // below the planners' so discretisation cannot make a
                                         // freshly verified answer look colliding
  double answer_speed_tolerance = 0.05;  // accepted relative excess over v_max / a_max (EAM's)
  // Answers longer than this are refused first: the geofence and collision checks walk an answer
  // in small time steps, and a hostile 4096-piece answer of 1e4 s pieces would take hours.
  double max_answer_duration_s = 120.0;
  // A collision found beyond the halfway point (plus this margin) of the committed trajectory is
  // left to the halfway replan, which comes first; nearer ones trigger EAM at once.
  bool defer_far_collisions = true;
  double collision_margin_s = 1.5;
  // While a stopping trajectory brakes, plans from its hard-braking states rarely fit the limits:
  // retries then wait this long between rounds instead of running on every map.
  double stop_retry_period_s = 0.3;
  // A collision the vehicle reaches later than this is not an emergency: the replan then asks the
  // mode awareness picks (SOM/FPM) rather than EAM, which would slow down around it.
  double emergency_horizon_s = 2.0;
  double stale_map_s = 0.5;            // LOCAL_MAP older than this (message clock) is stale
  double stale_odometry_s = 0.5;       // ODOMETRY older than this (message clock): no planning
  double start_escape_radius_m = 0.5;  // an answer starting in the check margin must leave it
                                       // within this distance of its start
  // EAM on a collision gets the rest of the committed trajectory as its reference only when more
  // than this is left of it after the new start.
  double reference_min_remaining_s = 0.2;
  double stop_min_speed_mps = 0.05;  // slower than this, a stale input needs no stop
  // With danger ahead and no usable answer, the stop waits while one begun this much later would
  // still end clear of the known obstacles (0: stop at once).
  double stop_decision_margin_s = 0.5;
  // ... and while it waits, each such round slows the committed trajectory along its path to this
  // share of its speed (1: off), so that the next rounds start slower.
  double failed_round_speed_ratio = 0.7;
  // ... and commits it only up to the latest point from which a stop still ends clear (less the
  // margin above), followed by that stop: the danger is answered at once (flyOnWithBackupStop).
  bool backup_stop = true;
  double braking_speed_mps = 0.1;  // a committed stop faster than this still brakes
  // The stuck detector (progress_monitor.hpp, stuckResponse).
  double progress_min_step_m = 0.5;     // progress: this much nearer to the goal than ever before
  double progress_new_ground_m = 1.0;   // ... or this far from the places flown (0: off)
  double stuck_after_s = 4.0;           // no progress this long: stuck
  double stuck_still_s = 1.0;           // ... or at rest this long, no mode's answer committed
  double stuck_retry_period_s = 1.0;    // retries while stuck come at most this often
  double backoff_min_distance_m = 1.0;  // a back-off target is at least this far away
  double retrace_speed_mps = 0.5;       // no mode answers a back-off: the way back flown this fast
  double backoff_clearance_m = 0.15;    // ... and this much clearer than inflation_m
  double give_up_s = 30.0;              // no progress this long: unreachable, hold
  double unreachable_retry_s = 5.0;     // while unreachable, one retry this often
  // A goal inside a mapped obstacle or its margin (inflation_m) moves to the nearest free point
  // within this radius (goal_placement.hpp); beyond it, it is refused.
  double goal_relocate_radius_m = 1.5;
  // Answer check (answer_check.hpp).
  double start_position_tolerance_m = 1e-3;  // an answer's start against the requested state
  double start_velocity_tolerance_mps = 1e-2;
  double start_acceleration_tolerance_mps2 = 5e-2;
  double check_step_s = 0.05;          // time step of the geofence walk
  double geofence_tolerance_m = 0.05;  // accepted excursion beyond the geofence
  double escape_step_s = 0.01;         // time step of the walk out of the start's margin
  // The planners keep mmh::kEscapeDepthTolerance on their own samples; this check samples in
  // time (escape_step_s, up to 3 cm apart at v_max), so it allows a little more between them.
  double escape_depth_tolerance_m = 0.03;
  Eigen::Vector3d geofence_min_m = Eigen::Vector3d(-1e3, -1e3, 0.0);
  Eigen::Vector3d geofence_max_m = Eigen::Vector3d(1e3, 1e3, 1e3);

  double horizonDistance() const { return max_vel_mps * planning_horizon_s; }
};

ArbiterParams loadArbiterParams(const Config& config);

}  // namespace mmh::arbiter
