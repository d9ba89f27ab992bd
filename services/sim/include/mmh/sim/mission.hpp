// Ground-truth mission metrics of docs/benchmark.md, accumulated step by step from what the vehicle
// actually flew: success (goal within tolerance, no collision), flight time from the first
// committed trajectory to arrival, arc length, jerk energy (exact per flown trajectory part),
// smallest clearance, and the time bound on the shortest collision-free path.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <vector>

#include "mmh/sim/sim_params.hpp"
#include "mmh/sim/vehicle.hpp"
#include "mmh/sim/world.hpp"

namespace mmh::sim {

struct MissionMetrics {
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d goal = Eigen::Vector3d::Zero();
  int64_t goal_id = 0;         // 0 until a GOAL message set it
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

  // Accounts one step: the parts flown since the last update, the vehicle's jumps so far, and
  // its state at now_utime. Returns true if reached or collided became true in this update.
  // Metrics stop changing once the goal is reached (until a new goal).
  bool update(int64_t now_utime, const Vehicle& vehicle, const std::vector<FlownPart>& flown);

  const MissionMetrics& metrics() const { return metrics_; }

 private:
  void computeBound();

  const World& world_;
  SimParams params_;
  MissionMetrics metrics_;
  double jumps_seen_m_ = 0.0;
  int jumps_seen_ = 0;
};

}  // namespace mmh::sim
