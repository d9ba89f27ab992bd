// mmh-sim as a message-driven node: advances the Simulator one step per step() call and publishes
// ODOMETRY (every step), POINTCLOUD (sensor rate) and MISSION_STATUS (status rate and on reach or
// collision); takes TRAJECTORY (the committed one) or, with --follow setpoint, SETPOINT, and GOAL
// (for the mission status), and ARBITER_STATUS for a goal the arbiter moved out of an obstacle
// (arrival is then measured there, within arbiter.goal_relocate_radius_m of the goal sent). No
// thread, no wall clock: mmh-stack calls step() in lock-step, main.cpp paces it in real time.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "mmh/arbiter_status_t.hpp"
#include "mmh/common/config.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/goal_t.hpp"
#include "mmh/mission_status_t.hpp"
#include "mmh/odometry_t.hpp"
#include "mmh/pointcloud_t.hpp"
#include "mmh/setpoint_t.hpp"
#include "mmh/sim/simulator.hpp"
#include "mmh/trajectory_t.hpp"

namespace mmh {

using SimOptions = sim::SimOptions;

class SimNode {
 public:
  // Builds the world (throws ConfigError for bad config, std::runtime_error for bad options).
  SimNode(ServiceContext& ctx, const Config& config, const SimOptions& options);

  // Advances simulated time by sim.step_s and publishes what is due; with publish_scans false
  // a due POINTCLOUD is not sent (counted as scans_skipped_late).
  void step(bool publish_scans = true);
  int64_t nowUtime() const { return sim_.nowUtime(); }
  const sim::MissionMetrics& metrics() const { return sim_.metrics(); }
  bool finished() const { return sim_.finished(); }
  const sim::Simulator& simulator() const { return sim_; }

  // Message builders (also used by tests).
  odometry_t makeOdometry() const;
  pointcloud_t makePointcloud(const sim::Scan& scan) const;
  mission_status_t makeMissionStatus() const;

 private:
  void onTrajectory(const trajectory_t& msg);
  void onGoal(const goal_t& msg);
  void onSetpoint(const setpoint_t& msg);
  void onArbiterStatus(const arbiter_status_t& msg);
  // A vehicle counter that grew since *seen: counted in HEARTBEAT and logged with what().
  void reportNew(const char* counter, int total, int* seen,
                 const std::function<std::string()>& what);

  ServiceContext& ctx_;
  sim::Simulator sim_;
  bool reported_reached_ = false, reported_collision_ = false;
  int jumps_seen_ = 0;
  int late_takeovers_seen_ = 0, lost_commits_seen_ = 0, jumps_after_loss_seen_ = 0;
  size_t arrivals_reported_ = 0;
};

}  // namespace mmh
