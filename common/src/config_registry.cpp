#include "mmh/common/config_registry.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

namespace mmh {
namespace {

KeySpec real(const std::string& name, double min, double max, const std::string& def,
             const std::string& doc) {
  KeySpec k;
  k.name = name;
  k.type = KeyType::kDouble;
  k.min = min;
  k.max = max;
  k.default_yaml = def;
  k.doc = doc;
  return k;
}

KeySpec integer(const std::string& name, double min, double max, const std::string& def,
                const std::string& doc) {
  KeySpec k = real(name, min, max, def, doc);
  k.type = KeyType::kInt;
  return k;
}

KeySpec vector3(const std::string& name, double min, double max, const std::string& def,
                const std::string& doc) {
  KeySpec k = real(name, min, max, def, doc);
  k.type = KeyType::kVector3;
  return k;
}

KeySpec flag(const std::string& name, const std::string& def, const std::string& doc) {
  KeySpec k = real(name, 0.0, 0.0, def, doc);
  k.type = KeyType::kBool;
  return k;
}

KeySpec choice(const std::string& name, std::vector<std::string> allowed, const std::string& def,
               const std::string& doc) {
  KeySpec k = real(name, 0.0, 0.0, def, doc);
  k.type = KeyType::kEnum;
  k.allowed = std::move(allowed);
  return k;
}

// A key a file may omit: the default then applies.
KeySpec optional(KeySpec k) {
  k.required = false;
  return k;
}

std::vector<KeySpec> buildKeys() {
  return {
      // vehicle
      real("vehicle.radius_m", 0.01, 5.0, "0.15",
           "Airframe radius: ground-truth collisions in mmh-sim"),
      real("vehicle.max_vel_mps", 0.1, 50.0, "3.0", "v_max: no planned trajectory is faster"),
      real("vehicle.max_acc_mps2", 0.1, 50.0, "2.0",
           "a_max: no planned trajectory accelerates harder"),
      // geofence
      vector3("geofence.min_m", -1e5, 1e5, "[-30.0, -30.0, 0.3]",
              "Lower corner of the box goals and committed trajectories stay in (world frame)"),
      vector3("geofence.max_m", -1e5, 1e5, "[30.0, 30.0, 2.7]",
              "Upper corner of that box (above geofence.min_m on every axis)"),
      // map
      real("map.resolution_m", 0.02, 1.0, "0.1", "Voxel edge of the local map"),
      vector3("map.window_size_m", 1.0, 200.0, "[32.0, 32.0, 4.0]",
              "Local map window around the vehicle (covers the planning range)"),
      real("map.inflation_m", 0.0, 5.0, "0.3",
           "Obstacles grow by this for planning (vehicle radius + safety margin)"),
      // sim
      real("sim.step_s", 1e-4, 0.1, "0.01", "Physics step; ODOMETRY is published every step"),
      real("sim.pointcloud_rate_hz", 0.1, 100.0, "15.0",
           "Sensor frames (POINTCLOUD) per simulated second"),
      real("sim.max_scan_lag_s", 0.0, 60.0, "0.2",
           "Real time: frames due further behind the wall clock are not sent"),
      real("sim.mission_status_rate_hz", 0.1, 100.0, "10.0",
           "MISSION_STATUS rate (also sent on reach / collision)"),
      real("sim.goal_tolerance_m", 0.01, 10.0, "0.3",
           "Reached = vehicle centre within this distance of the goal"),
      flag("sim.stop_on_collision", "true", "The mission is finished at the first collision"),
      real("sim.max_yaw_rate_dps", 1.0, 3600.0, "120.0", "Yaw rate limit"),
      real("sim.yaw_time_constant_s", 0.0, 10.0, "0.2", "First-order lag of the yaw"),
      real("sim.yaw_lookahead_s", 0.01, 10.0, "0.5",
           "Yaw faces the trajectory point this far ahead"),
      real("sim.yaw_lookahead_min_m", 0.0, 10.0, "0.2",
           "... or a later one at least this far away horizontally (creeping)"),
      integer("sim.free_ray_stride", 0, 1000, "1",
              "Every k-th no-return ray is sent as a far point (clears free space; 0 = none)"),
      integer("sim.depth.width_px", 2, 4096, "160", "Depth camera width"),
      integer("sim.depth.height_px", 2, 4096, "120", "Depth camera height"),
      real("sim.depth.hfov_deg", 1.0, 170.0, "80.0", "Depth camera horizontal field of view"),
      real("sim.depth.vfov_deg", 1.0, 170.0, "60.0", "Depth camera vertical field of view"),
      real("sim.depth.range_m", 0.1, 100.0, "4.5", "Depth camera range"),
      real("sim.depth.range_noise_m", 0.0, 1.0, "0.02",
           "Standard deviation of the Gaussian range noise (depth camera)"),
      integer("sim.lidar.horizontal_rays", 1, 10000, "360", "LiDAR rays over 360 deg"),
      integer("sim.lidar.vertical_rays", 1, 1000, "56", "LiDAR rays between vmin_deg and vmax_deg"),
      real("sim.lidar.vmin_deg", -90.0, 90.0, "-7.0", "Lowest LiDAR elevation"),
      real("sim.lidar.vmax_deg", -90.0, 90.0, "52.0",
           "Highest LiDAR elevation (not below sim.lidar.vmin_deg)"),
      real("sim.lidar.range_m", 0.1, 200.0, "5.0", "LiDAR range"),
      real("sim.lidar.range_noise_m", 0.0, 1.0, "0.02",
           "Standard deviation of the Gaussian range noise (LiDAR)"),
      real("sim.pcd_voxel_m", 0.005, 1.0, "0.05", "PCD worlds: voxel edge for ray casting"),
      real("sim.bound_grid_m", 0.02, 1.0, "0.1",
           "PCD worlds: A* grid of the shortest-path time bound"),
      real("sim.tracking.bandwidth_hz", 0.05, 50.0, "1.0",
           "--follow setpoint: natural frequency of the controller's position loop"),
      real("sim.tracking.damping_ratio", 0.1, 5.0, "1.0",
           "--follow setpoint: damping of that loop (1: critically damped)"),
      real("sim.tracking.max_acc_mps2", 0.1, 100.0, "4.0",
           "--follow setpoint: the airframe's acceleration limit"),
      real("sim.tracking.setpoint_timeout_s", 0.01, 10.0, "0.1",
           "--follow setpoint: a setpoint is carried forward this long, then the point held"),
      // mission
      real("mission.pass_tolerance_m", 0.05, 50.0, "1.0",
           "A waypoint passed at speed is reached within this distance (unless it sets its own)"),
      real("mission.stop_tolerance_m", 0.05, 50.0, "0.3",
           "A stop, and the last waypoint, is reached within this distance (unless it sets its "
           "own)"),
      real("mission.stop_speed_mps", 0.01, 5.0, "0.2",
           "... and only when the vehicle is slower than this"),
      // setpoint
      real("setpoint.rate_hz", 1.0, 1000.0, "100.0", "SETPOINT messages per second"),
      real("setpoint.watchdog_s", 0.1, 60.0, "2.5",
           "No TRAJECTORY and no arbiter HEARTBEAT this long: brake to a hover"),
      real("setpoint.yaw_lookahead_s", 0.01, 10.0, "0.5",
           "Yaw points at the trajectory point this far ahead"),
      real("setpoint.yaw_lookahead_min_m", 0.0, 10.0, "0.2",
           "... or a later one at least this far away horizontally (creeping)"),
      real("setpoint.max_yaw_rate_dps", 1.0, 3600.0, "90.0", "Yaw rate limit of the setpoints"),
      // mapping
      real("mapping.keyframe_period_s", 0.05, 60.0, "1.0",
           "A whole-window LOCAL_MAP at least this often"),
      integer("mapping.delta_repeat", 1, 16, "5",
              "A delta repeats this many deltas' cells: receivers bridge delta_repeat - 1 losses"),
      real("mapping.window_recenter_m", 0.0, 50.0, "1.0",
           "The window moves when the vehicle is this far off its centre"),
      real("mapping.max_range_m", 0.1, 100.0, "10.0",
           "Farther returns only clear free space up to this range"),
      integer("mapping.max_points", 1, 4'000'000, "500000",
              "Scans with more points are rejected (counter scan_too_large)"),
      real("mapping.prob_hit", 0.5001, 0.999, "0.7", "Occupancy probability update per hit"),
      real("mapping.prob_miss", 0.001, 0.4999, "0.4", "Occupancy probability update per miss"),
      real("mapping.clamp_min", 0.001, 0.4999, "0.12", "Lower clamp of the occupancy probability"),
      real("mapping.clamp_max", 0.5001, 0.999, "0.97", "Upper clamp of the occupancy probability"),
      real("mapping.occupancy_threshold", 0.001, 0.999, "0.5",
           "Occupied above this probability (within [clamp_min, clamp_max])"),
      // awareness
      real("awareness.sensor_range_m", 0.1, 100.0, "4.5", "r: the sensing ray is clipped to this"),
      real("awareness.narrow_probe_dist_m", 0.05, 10.0, "0.8",
           "Narrow-space test (BothSideJudge) probe distance; also used by EAM and the arbiter"),
      // fpm
      real("fpm.time_weight", 1e-3, 1e6, "20.0", "rho in J = int |jerk|^2 dt + rho T"),
      real("fpm.penalty_weight", 1.0, 1e9, "1.0e6", "Weight of the speed / acceleration penalties"),
      real("fpm.limit_margin_ratio", 0.0, 0.2, "0.005",
           "Guess and penalties stay this fraction below the limits"),
      integer("fpm.samples_per_piece", 2, 100, "8", "Penalty samples per polynomial piece"),
      integer("fpm.max_evaluations", 10, 100000, "12",
              "Cost evaluations per L-BFGS run (x5 with waypoints)"),
      // som: optional keys (tuning; the defaults are the tested values)
      optional(real("som.time_weight", 1e-3, 1e7, "20.0", "rho in J = int |jerk|^2 dt + rho T")),
      optional(integer("som.astar_max_expansions", 1000, 50'000'000, "200000",
                       "A* budget on the inflated grid")),
      optional(real("som.astar_heuristic_weight", 1.0, 10.0, "2.0",
                    "Weighted A*: fewer expansions (the optimiser straightens the path)")),
      optional(real("som.start_escape_radius_m", 0.0, 5.0, "0.5",
                    "A start inside the inflation margin may leave it within this distance")),
      optional(real("som.start_escape_clearance_m", 0.0, 5.0, "0.28",
                    "... only outwards, never nearer to occupied cells than the start or this")),
      optional(real("som.unknown_near_cost_cells", 0.0, 1000.0, "10.0",
                    "A* cost (in cell steps) of entering an unknown cell near the start, where the "
                    "camera has not looked (0: unknown space is free everywhere)")),
      optional(real("som.unknown_near_radius_m", 0.0, 50.0, "2.5",
                    "... a cell whose centre lies within this distance of the start")),
      optional(real("som.clearance_cost_cells", 0.0, 100.0, "5.0",
                    "A* cost (in cell steps) of a cell next to the inflated obstacles, so that the "
                    "path keeps to the middle of wide gaps (0: off)")),
      optional(real("som.clearance_width_m", 0.05, 2.0, "0.3",
                    "... falling linearly to 0 at this clearance from them")),
      optional(real("som.clearance_free_radius_m", 0.0, 50.0, "2.5",
                    "... and none within this distance of the start, where the start state "
                    "decides the way")),
      optional(flag("som.clearance_compare", "true",
                    "... and plan along both that path and the shortest, keeping the answer of "
                    "lower cost (jerk energy + time_weight x duration); false: prefer that path")),
      optional(flag("som.clearance_compare_parallel", "false",
                    "... planning the two paths on two threads: the same answer, sooner on a "
                    "computer with a core to spare, later on one whose cores are busy")),
      optional(real("som.lead_min_speed_mps", 0.0, 100.0, "1.0",
                    "A start at least this fast whose A* path turns away sharply also tries a path "
                    "that first goes on ahead; the faster verified answer wins")),
      optional(
          real("som.lead_min_turn_deg", 0.0, 180.0, "45.0",
               "... when the path's first leg turns away from the velocity by more than this")),
      optional(real("som.lead_reach", 0.0, 10.0, "1.5",
                    "... from a point at most this many braking distances ahead (0: never)")),
      optional(real("som.corridor_box_margin_m", 0.3, 20.0, "1.0",
                    "Obstacle points / polytope bound: seed box grown by this (x, y)")),
      optional(real("som.corridor_box_margin_z_m", 0.2, 20.0, "0.5", "... and by this vertically")),
      optional(real("som.corridor_seed_length_m", 0.2, 50.0, "3.0",
                    "Longest seed segment of one polytope")),
      optional(integer("som.corridor_iterations", 1, 10, "2",
                       "Hyperplane rounds (an inscribed-ellipsoid step between two)")),
      optional(real("som.corridor_early_round_margin_m", 0.0, 20.0, "0.6",
                    "Rounds before the last look only this far around the seed (0: whole box)")),
      optional(real("som.corridor_overlap_backoff_m", 0.0, 5.0, "0.5",
                    "The next seed starts this far back, so polytopes overlap usefully")),
      optional(real("som.corridor_junction_margin_m", 0.0, 1.0, "0.1",
                    "A junction point lies at least this far inside both polytopes")),
      optional(integer("som.corridor_max_polytopes", 1, 1000, "48", "Polytopes per corridor")),
      optional(real("som.piece_length_m", 0.2, 50.0, "3.0",
                    "Pieces per polytope = ceil(length / this)")),
      optional(integer("som.samples_per_piece", 2, 128, "6", "Penalty samples per piece")),
      optional(real("som.weight_corridor", 1.0, 1e9, "1.0e5", "Corridor penalty weight")),
      optional(real("som.weight_velocity", 1.0, 1e9, "1.0e3", "Speed limit penalty weight")),
      optional(
          real("som.weight_acceleration", 1.0, 1e9, "1.0e3", "Acceleration limit penalty weight")),
      optional(real("som.penalty_smoothing", 1e-6, 1.0, "0.01",
                    "Width of the smoothed-L1 penalty near zero")),
      optional(real("som.limit_margin", 0.0, 0.2, "0.01",
                    "Aim this much (relative) below v_max / a_max")),
      optional(
          real("som.corridor_margin_m", 0.0, 0.5, "0.03", "Aim this far inside the polytopes")),
      optional(integer("som.max_evaluations", 10, 100000, "60", "Cost evaluations per L-BFGS run")),
      optional(integer("som.extra_rounds", 0, 10, "3",
                       "Runs with raised weights while the corridor or limits are violated")),
      optional(integer("som.extra_round_evaluations", 1, 100000, "40",
                       "Cost evaluations per extra round")),
      optional(real("som.extra_round_weight_factor", 1.0, 1000.0, "10.0",
                    "Weight factor of each extra round")),
      optional(real("som.extra_round_limit_excess", 0.0, 1.0, "0.005",
                    "Moving start: relative limit excess that triggers an extra round")),
      optional(real("som.repair_tolerance", 0.0, 0.05, "0.002",
                    "Durations stretch until the exact maxima are within this of the limits")),
      optional(real("som.max_repair_stretch", 1.0, 10.0, "4.0",
                    "... by at most this factor, and only while it helps")),
      optional(real("som.rel_cost_tolerance", 0.0, 0.1, "1.0e-3",
                    "Early stop: relative cost change per L-BFGS step")),
      optional(integer("som.lbfgs_memory", 1, 64, "8", "L-BFGS memory")),
      optional(real("som.first_step", 1e-4, 100.0, "0.3", "Length of L-BFGS's first step")),
      optional(real("som.verify_limit_tolerance", 0.0, 0.2, "0.01",
                    "Verification: relative tolerance on v_max / a_max (exact maxima)")),
      optional(real("som.verify_corridor_tolerance_m", 0.0, 0.5, "0.02",
                    "Verification: tolerance outside the corridor")),
      optional(flag("som.publish_debug", "false",
                    "Publish the A* path and corridor of each answer on PLAN_DEBUG (viewer)")),
      // eam
      real("eam.knot_span_s", 0.02, 2.0, "0.2", "Initial knot span of the uniform cubic B-spline"),
      optional(real("eam.fine_knot_span_s", 0.0, 2.0, "0.0",
                    "A plan that ends in collision or fails verification is made once more with "
                    "this finer knot span (0: off)")),
      real("eam.lambda_smooth_open", 1e-9, 1e9, "1.0", "lambda1 (smoothness), open space"),
      real("eam.lambda_smooth_narrow", 1e-9, 1e9, "0.2", "lambda1 (smoothness), narrow space"),
      real("eam.lambda_collision_open", 1e-9, 1e12, "200000.0", "lambda2 (collision), open space"),
      real("eam.lambda_collision_narrow", 1e-9, 1e12, "1000000.0",
           "lambda2 (collision), narrow space"),
      real("eam.lambda_feasibility", 0.0, 1e12, "10.0", "lambda3 (speed / acceleration limits)"),
      real("eam.clearance_m", 0.0, 2.0, "0.1",
           "Asked beyond each anchor plane, on top of map.inflation_m"),
      optional(real("eam.geofence_margin_m", 0.0, 1.0, "0.05",
                    "The optimiser's walls stand this far inside the geofence (its penalty is "
                    "soft)")),
      real("eam.window_margin_s", 0.0, 100.0, "2.5",
           "Optimise control points within this time of a collision"),
      flag("eam.guide_warm_start", "true", "Start from the A* guide path on colliding stretches"),
      real("eam.merge_gap_s", 0.0, 100.0, "2.0",
           "Colliding stretches closer than this share one A* search"),
      integer("eam.max_rebound_rounds", 1, 50, "10",
              "Optimisations with new {p, v} pairs (collision checks between)"),
      integer("eam.max_refine_rounds", 0, 20, "5",
              "Time re-allocations while v_max / a_max are broken"),
      integer("eam.max_restarts", 0, 10, "1",
              "When the rounds run out: again, one A* guide for all collisions"),
      integer("eam.max_iterations", 10, 100000, "200", "L-BFGS cost evaluations per optimisation"),
      real("eam.optimizer_ftol_rel", 1e-12, 0.5, "0.01",
           "L-BFGS stops when a step improves the cost by less than this (relative)"),
      real("eam.limit_tolerance_ratio", 0.0, 0.5, "0.05",
           "Accepted excess over v_max / a_max (emergency)"),
      integer("eam.astar_max_expansions", 1000, 100'000'000, "200000",
              "A* budget per colliding stretch"),
      real("eam.astar_heuristic_weight", 1.0, 10.0, "1.5",
           "Weighted A* for guides (1 = shortest path)"),
      real("eam.astar_slot_width_m", 0.0, 5.0, "0.3",
           "A guide cell with inflated obstacles this close on both sides is in a slot"),
      real("eam.astar_slot_cost", 0.0, 1000.0, "10.0",
           "Extra A* cost per voxel in a slot when avoiding slots"),
      real("eam.astar_slab_margin_m", 0.0, 100.0, "0.0",
           "A* first tries the stretch's voxel layers widened by this"),
      real("eam.astar_box_margin_m", 0.1, 1000.0, "3.0",
           "... within the stretch's end points' box widened by this"),
      real("eam.start_escape_radius_m", 0.0, 2.0, "0.3",
           "A start inside the inflated margin may cross it this far"),
      real("eam.start_escape_clearance_m", 0.0, 2.0, "0.28",
           "... only outwards, never nearer to occupied cells than the start or this"),
      optional(real("eam.start_forced_deviation_m", 0.0, 0.2, "0.04",
                    "Margin cells an answer meets while its start state holds it within this of "
                    "its way (1/2 a_max t^2) keep only the escape clearance")),
      optional(
          flag("eam.publish_debug", "false",
               "Publish the A* guides and {p, v} pairs of each answer on PLAN_DEBUG (viewer)")),
      // arbiter
      choice("arbiter.policy", {"mmh", "mmh-no-lazy", "mmh-no-awareness", "ego", "som"}, "mmh",
             "Method: the full MMH, its ablations, or a baseline (EAM / SOM alone)"),
      real("arbiter.planning_horizon_s", 0.5, 60.0, "5.0",
           "Local target: at most the distance flown in this time at v_max"),
      real("arbiter.replan_lead_s", 0.0, 1.0, "0.05",
           "A new trajectory takes effect this long after its request"),
      real("arbiter.answer_deadline_s", 0.001, 2.0, "0.04",
           "Answers arriving later are ignored (<= arbiter.replan_lead_s)"),
      real("arbiter.latency_window_s", 0.5, 600.0, "10",
           "The latency budget reads the answers and maps of this last stretch of time"),
      real("arbiter.latency_headroom", 1.0, 10.0, "1.5",
           "Late answers lengthen the deadline to this x their p99 latency"),
      real("arbiter.max_answer_deadline_s", 0.001, 2.0, "0.2",
           "The longest the deadline (and with it the replan lead) may grow at full speed"),
      real("arbiter.max_slowed_answer_deadline_s", 0.001, 5.0, "1.0",
           "Past max_answer_deadline_s the deadline may grow to this, the speed lowered so that "
           "the vehicle still stops within awareness.sensor_range_m"),
      real("arbiter.slowdown_tolerance", 0.0, 1.0, "0.05",
           "The committed trajectory is slowed down when it is faster than the lowered speed "
           "limit by more than this fraction of it"),
      real("arbiter.max_map_age_s", 0.01, 5.0, "0.25",
           "LOCAL_MAP older than this on arrival (p99) marks the arbiter degraded"),
      choice("arbiter.parallel_modes", {"none", "collision", "always"}, "none",
             "When SOM and EAM are asked together"),
      optional(real("arbiter.score_jerk_weight_s", 0.0, 10.0, "0.0",
                    "An answer's score: its time to the goal plus this many seconds per m^2/s^5 "
                    "of its jerk energy (0: time only)")),
      real("arbiter.goal_tolerance_m", 0.05, 5.0, "0.3", "The goal is reached within this"),
      real("arbiter.fixed_replan_distance_m", 0.1, 50.0, "1.5",
           "ego / som / mmh-no-lazy: replan after this much progress"),
      real("arbiter.stop_retry_period_s", 0.0, 10.0, "0.3",
           "While braking in a stop, plan again at most this often"),
      real("arbiter.emergency_horizon_s", 0.0, 60.0, "2.0",
           "Collisions reached later than this go to the awareness mode, not EAM"),
      real("arbiter.stale_map_s", 0.05, 60.0, "0.5",
           "LOCAL_MAP older than this (message clock): stop until maps return"),
      real("arbiter.stale_odometry_s", 0.02, 60.0, "0.5",
           "ODOMETRY older than this: no planning, stop until it returns"),
      real("arbiter.start_escape_radius_m", 0.0, 5.0, "0.5",
           "An answer starting in the check margin must leave it within this distance"),
      real("arbiter.check_inflation_m", 0.0, 5.0, "0.25",
           "Inflation of the arbiter's own collision checks (<= map.inflation_m); SOM keeps "
           "answers out of the cells it blocks"),
      real("arbiter.answer_limit_tolerance", 0.0, 0.5, "0.05",
           "Accepted relative excess of an answer over v_max / a_max"),
      real("arbiter.max_answer_duration_s", 1.0, 3600.0, "120.0",
           "Longer answers are refused before any check that walks them"),
      flag("arbiter.defer_far_collisions", "true",
           "A collision beyond the committed trajectory's halfway point waits for that replan"),
      real("arbiter.collision_margin_s", 0.0, 30.0, "1.5", "... beyond halfway plus this margin"),
      real("arbiter.replan_fraction", 0.05, 1.0, "0.5",
           "Lazy rule (1): replan once this share of the committed trajectory has been flown"),
      real("arbiter.slow_plan_ratio", 1.0, 100.0, "2.0",
           "A trajectory to the goal slower than this x the bound of its straight length is "
           "replanned at its halfway point too"),
      real("arbiter.halfway_keep_margin_s", 0.0, 3600.0, "0.5",
           "A halfway replan keeps the committed trajectory when the answer's estimated arrival "
           "at the goal is later than the committed one's by more than this"),
      real("arbiter.halfway_keep_min_left_s", 0.0, 3600.0, "2.0",
           "... but only while more than this of the committed trajectory is left"),
      real("arbiter.known_space_margin_m", 0.0, 10.0, "0.3",
           "An answer must stay in mapped space within its stopping distance plus this"),
      real("arbiter.known_space_lead_s", 0.0, 5.0, "0.1",
           "... that stopping distance counted from the point the answer reaches this long (plus "
           "the replan lead) after its start, at the speed there: the next map checks it again"),
      real("arbiter.hidden_face_m", 0.0, 2.0, "0.3",
           "... and beside the centre line, within vehicle.radius_m, no unknown cell this close to "
           "an occupied cell (a mapped obstacle's unseen side; 0: the centre line only)"),
      real("arbiter.hidden_face_reach_m", 0.0, 10.0, "0.5",
           "... within this much path from the vehicle (farther ahead the sensor sees those cells "
           "on the way)"),
      real("arbiter.slow_plan_replan_s", 0.05, 3600.0, "1.0",
           "A trajectory slower than slow_plan_ratio x its bound is replanned no later than this "
           "after its commit"),
      real("arbiter.reference_min_remaining_s", 0.0, 10.0, "0.2",
           "EAM on a collision re-optimises the committed rest only when more than this is left"),
      real("arbiter.stop_min_speed_mps", 0.0, 1.0, "0.05",
           "A stale input stops the vehicle only when it is faster than this"),
      real("arbiter.stop_decision_margin_s", 0.0, 5.0, "0.5",
           "No usable answer, danger ahead: stop once a stop begun this much later would collide"),
      real("arbiter.failed_round_speed_ratio", 0.1, 1.0, "0.7",
           "... meanwhile slow the committed path to this share of its speed per round (1: off)"),
      flag("arbiter.backup_stop", "true",
           "... and commit the path up to a verified stop clear of the danger (the backup stop)"),
      real("arbiter.progress_min_step_m", 0.01, 10.0, "0.5",
           "Progress: this much nearer to the goal than ever before"),
      optional(real("arbiter.progress_new_ground_m", 0.0, 20.0, "1.0",
                    "... or this far from every place flown since the goal was set (0: off)")),
      real("arbiter.stuck_after_s", 0.5, 600.0, "4.0",
           "No progress this long: stuck (retries throttled, one back-off)"),
      optional(real("arbiter.stuck_still_s", 0.1, 600.0, "1.0",
                    "... or at rest this long with no mode's answer committed (at least "
                    "stuck_after_s: off)")),
      real("arbiter.stuck_retry_period_s", 0.0, 60.0, "1.0",
           "While stuck, retries come at most this often"),
      real("arbiter.backoff_min_distance_m", 0.1, 20.0, "1.0",
           "A back-off target (recently flown free space) is at least this far away"),
      real("arbiter.backoff_clearance_m", 0.0, 2.0, "0.15",
           "... and keeps this much more than map.inflation_m from obstacles"),
      real("arbiter.retrace_speed_mps", 0.05, 5.0, "0.5",
           "No mode answers a back-off: the vehicle flies back the way it came at about this "
           "speed"),
      real("arbiter.goal_relocate_radius_m", 0.0, 10.0, "1.5",
           "A goal inside an obstacle's margin moves to the nearest free point this near, else is "
           "refused"),
      real("arbiter.give_up_s", 1.0, 3600.0, "30.0",
           "No progress this long: the goal is unreachable, the vehicle holds"),
      real("arbiter.unreachable_retry_s", 0.1, 600.0, "5.0",
           "While unreachable, one retry this often"),
      real("arbiter.braking_speed_mps", 0.0, 1.0, "0.1",
           "A committed stop faster than this still brakes (retries are throttled)"),
      real("arbiter.start_position_tolerance_m", 0.0, 0.1, "0.001",
           "An answer's start position against the requested state"),
      real("arbiter.start_velocity_tolerance_mps", 0.0, 1.0, "0.01",
           "An answer's start velocity against the requested state"),
      real("arbiter.start_acceleration_tolerance_mps2", 0.0, 5.0, "0.05",
           "An answer's start acceleration against the requested state"),
      real("arbiter.check_step_s", 0.001, 0.5, "0.05", "Time step of the answer's geofence check"),
      real("arbiter.geofence_tolerance_m", 0.0, 1.0, "0.05",
           "Accepted excursion of an answer beyond the geofence"),
      real("arbiter.escape_step_s", 0.001, 0.1, "0.01",
           "Time step of the walk out of a start inside the check margin"),
      real("arbiter.escape_depth_tolerance_m", 0.0, 0.2, "0.03",
           "How much nearer to the obstacle that walk may come between its samples"),
  };
}

std::vector<SectionSpec> buildSections() {
  return {
      {"vehicle", "Airframe and dynamic limits, shared by every service."},
      {"geofence", "The box goals and committed trajectories must stay in."},
      {"map", "Local map geometry, shared by mmh-mapping and the map consumers."},
      {"sim", "mmh-sim: physics, sensors and mission status."},
      {"mission",
       "Missions of several waypoints: mmh-goal, mmh-stack, the simulator's ground truth."},
      {"setpoint", "mmh-setpoint: the trajectory server that samples TRAJECTORY into SETPOINT."},
      {"mapping", "mmh-mapping: occupancy fusion and LOCAL_MAP publication."},
      {"awareness", "mmh-awareness: the environmental awareness test."},
      {"fpm", "mmh-fpm: Fast Planning Mode optimiser."},
      {"som", "mmh-som: Standard Optimization Mode (A*, corridor, MINCO). Keys may be omitted."},
      {"eam", "mmh-eam: Emergency Avoidance Mode (B-spline rebound optimisation)."},
      {"arbiter", "mmh-arbiter: mode choice, replanning policy and answer checks."},
  };
}

size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t substitution = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      diagonal = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitution});
    }
  }
  return row[b.size()];
}

const std::unordered_map<std::string, size_t>& keyIndex() {
  static const std::unordered_map<std::string, size_t> index = [] {
    std::unordered_map<std::string, size_t> m;
    for (size_t i = 0; i < configKeys().size(); ++i) m.emplace(configKeys()[i].name, i);
    return m;
  }();
  return index;
}

}  // namespace

std::string KeySpec::section() const {
  return name.substr(0, name.find('.'));
}

std::string KeySpec::unit() const {
  static const std::vector<std::pair<std::string, std::string>> kSuffixUnits = {
      {"_mps2", "m/s^2"}, {"_mps", "m/s"}, {"_dps", "deg/s"}, {"_deg", "deg"},
      {"_hz", "Hz"},      {"_px", "px"},   {"_m", "m"},       {"_s", "s"},
  };
  for (const auto& [suffix, unit] : kSuffixUnits) {
    if (name.size() > suffix.size() &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      return unit;
  }
  return "";
}

std::string KeySpec::typeName() const {
  switch (type) {
    case KeyType::kDouble:
      return "double";
    case KeyType::kInt:
      return "int";
    case KeyType::kBool:
      return "bool";
    case KeyType::kEnum:
      return "enum";
    case KeyType::kVector3:
      return "vector3";
  }
  return "?";
}

std::string KeySpec::rangeText() const {
  std::ostringstream s;
  switch (type) {
    case KeyType::kBool:
      return "true, false";
    case KeyType::kEnum:
      for (size_t i = 0; i < allowed.size(); ++i) s << (i ? ", " : "") << allowed[i];
      return s.str();
    case KeyType::kVector3:
      s << "[" << min << ", " << max << "] each";
      return s.str();
    case KeyType::kDouble:
    case KeyType::kInt:
      break;
  }
  s << "[" << min << ", " << max << "]";
  return s.str();
}

const std::vector<KeySpec>& configKeys() {
  static const std::vector<KeySpec> keys = buildKeys();
  return keys;
}

const std::vector<SectionSpec>& configSections() {
  static const std::vector<SectionSpec> sections = buildSections();
  return sections;
}

const KeySpec* findConfigKey(const std::string& name) {
  const auto it = keyIndex().find(name);
  return it == keyIndex().end() ? nullptr : &configKeys()[it->second];
}

const KeySpec& registeredConfigKey(const std::string& name) {
  const KeySpec* spec = findConfigKey(name);
  if (spec == nullptr) {
    throw std::logic_error("configuration key '" + name +
                           "' is read but not registered (common/src/config_registry.cpp)");
  }
  return *spec;
}

bool isConfigSection(const std::string& prefix) {
  const std::string dotted = prefix + ".";
  return std::any_of(configKeys().begin(), configKeys().end(), [&](const KeySpec& k) {
    return k.name.compare(0, dotted.size(), dotted) == 0;
  });
}

std::string nearestConfigKey(const std::string& name) {
  std::string best;
  size_t best_distance = std::string::npos;
  const auto consider = [&](const std::string& candidate) {
    const size_t d = editDistance(name, candidate);
    if (d < best_distance) {
      best_distance = d;
      best = candidate;
    }
  };
  for (const KeySpec& k : configKeys()) {
    consider(k.name);
    // Its sections too: a misspelt section name ("vehicel") is reported alone.
    for (size_t dot = k.name.find('.'); dot != std::string::npos; dot = k.name.find('.', dot + 1))
      consider(k.name.substr(0, dot));
  }
  // Beyond about a third of the name it is another word, not a misspelling.
  return best_distance <= std::max<size_t>(2, name.size() / 3) ? best : "";
}

}  // namespace mmh
