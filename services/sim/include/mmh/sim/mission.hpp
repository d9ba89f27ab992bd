// Ground-truth mission metrics of docs/benchmark.md, accumulated step by step from what the vehicle
// actually flew: success (goal within tolerance, no collision), flight time from the first
// committed trajectory to arrival, arc length, jerk energy (exact per flown trajectory part),
// smallest clearance, and the time bound on the shortest collision-free path; for missions of
// several waypoints every arrival, and while following setpoints the tracking error.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <vector>

#include "mmh/sim/sim_params.hpp"
#include "mmh/sim/vehicle.hpp"
#include "mmh/sim/world.hpp"

namespace mmh::sim {

// A GOAL as the simulator takes it: one goal, or one waypoint of a mission (goal_t's fields).
struct MissionGoal {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  int64_t goal_id = 0;
  int waypoint_index = 0;
  int num_waypoints = 0;     // 0 or 1: a single goal, reached within sim.goal_tolerance_m
  double tolerance_m = 0.0;  // 0: sim.goal_tolerance_m
  bool stop = false;
  bool isLastWaypoint() const { return waypoint_index + 1 >= num_waypoints; }
};

struct WaypointArrival {
  int waypoint_index = 0;
  double flight_time_s = 0.0;
  double speed_mps = 0.0;
};

struct MissionMetrics {
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d goal = Eigen::Vector3d::Zero();
  int64_t goal_id = 0;  // 0 until a GOAL message set it
  // The arbiter moved the goal out of an obstacle (ARBITER_STATUS OUTCOME_GOAL_MOVED) and arrival
  // is measured at moved_goal (see MissionMonitor::acceptMovedGoal); `goal` stays the goal sent.
  bool goal_moved = false;
  Eigen::Vector3d moved_goal = Eigen::Vector3d::Zero();
  bool started = false;        // the first committed trajectory has started
  bool reached = false;        // within the tolerance of the goal, no collision before
  bool collided = false;       // the vehicle sphere touched an obstacle at some step
  double flight_time_s = 0.0;  // first trajectory start to arrival (to now while flying)
  double distance_m = 0.0;     // arc length flown (plus any trajectory jumps)
  double energy = 0.0;         // integral of |jerk|^2 dt over the flown parts (m^2/s^5)
  double min_clearance_m = std::numeric_limits<double>::infinity();  // centre to obstacle
  double shortest_path_m = -1.0;  // shortest collision-free path start -> goal (-1: none)
  double time_bound_s = -1.0;     // restToRestTime(shortest_path_m, v_max, a_max)
  int64_t start_utime = -1, arrival_utime = -1, collision_utime = -1;
  Eigen::Vector3d collision_position = Eigen::Vector3d::Zero();
  int trajectory_jumps = 0;
  // Missions: the current waypoint, and every arrival in order (reached: at the last one).
  int waypoint_index = 0;
  int num_waypoints = 0;
  std::vector<WaypointArrival> arrivals;
  // Following setpoints: distance from the vehicle to the reference, from the start of the
  // flight to arrival.
  bool follows_setpoints = false;
  double tracking_error_rms_m = 0.0;
  double tracking_error_max_m = 0.0;
  int64_t tracking_samples = 0;
};

// |jerk|^2 integrated over [t0, t1] of the trajectory's own time, exactly (polynomial integral).
double jerkEnergy(const Trajectory& trajectory, double t0, double t1);

class MissionMonitor {
 public:
  // Computes the shortest path start -> goal in `world` (kept by reference) and its time bound.
  MissionMonitor(const World& world, const SimParams& params, const Eigen::Vector3d& start,
                 const Eigen::Vector3d& goal);

  // A goal from a GOAL message. A different position than the current goal starts a new leg:
  // reached is cleared and the bound recomputed; the same position only records the id.
  void setGoal(const Eigen::Vector3d& goal, int64_t goal_id);
  // The same for a waypoint of a mission: it is arrived at by mission.hpp's rule (its tolerance,
  // its stop), the mission reached at the last one. The time bound is that of the last leg's goal
  // from the start (it means something for a single goal only).
  void setMissionGoal(const MissionGoal& goal);
  // The arbiter moved the current goal to `moved` (out of an obstacle's margin). Arrival is then
  // measured at `moved`, the point the planners fly to, but only if it lies within radius_m
  // (arbiter.goal_relocate_radius_m) of the goal sent: the ground truth cannot be talked into
  // "reached" anywhere else. Returns whether it was accepted. A new goal position resets it.
  bool acceptMovedGoal(const Eigen::Vector3d& moved, double radius_m);

  // Accounts one step: the parts flown since the last update, the vehicle's jumps so far, and
  // its state at now_utime. Returns true if reached or collided became true in this update.
  // Metrics stop changing once the goal is reached (until a new goal).
  bool update(int64_t now_utime, const Vehicle& vehicle, const std::vector<FlownPart>& flown);

  const MissionMetrics& metrics() const { return metrics_; }

 private:
  void computeBound();

  // The current goal is reached: a single goal within sim.goal_tolerance_m, a waypoint by its rule.
  bool goalReachedNow(const Eigen::Vector3d& position, double speed_mps) const;

  const World& world_;
  SimParams params_;
  MissionMetrics metrics_;
  MissionGoal goal_;
  Eigen::Vector3d arrival_point_ = Eigen::Vector3d::Zero();  // the goal, or the moved goal
  bool arrived_at_goal_ = false;
  double jumps_seen_m_ = 0.0;
  double model_distance_seen_m_ = 0.0, model_energy_seen_ = 0.0;
  double tracking_error_sum_sq_ = 0.0;
};

}  // namespace mmh::sim
