// mmh-stack's engine: every service of one or more vehicles hosted in one process on one
// memq:// LCM, with the simulator in lock-step. Messages are delivered synchronously after each
// simulation step, so a flight runs faster than real time, planning takes no simulated time, and
// the same seed gives the same flight. Used by mmh-stack, mmh-bench, mmh-replay and the tests.
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mmh/common/config.hpp"
#include "mmh/common/mission.hpp"
#include "mmh/sim/mission.hpp"
#include "mmh/sim/simulator.hpp"
#include "stop_census.hpp"

namespace mmh {

struct StackOptions {
  Config config;
  sim::SimOptions sim;
  std::string prefix;  // channel prefix of the vehicle
  // Vehicles in the one lock-step simulation. With more than one, vehicle i (from 1) has the
  // prefix `prefix + "UAV<i>_"`, forest seed sim.seed + i - 1 and noise seed
  // sim.noise_seed + i - 1: its own stack of services and its own world, on the same bus.
  int vehicles = 1;
  std::string policy;        // empty: arbiter.policy from the config
  double timeout_s = 120.0;  // simulated seconds before giving up
  std::string log_path;      // if set: an LCM log of every message (event time = sim time)
  double map_loss = 0.0;     // test switch: share of LOCAL_MAP messages the planners lose
  uint64_t loss_seed = 1;
  // A mission (mmh/common/mission.hpp): its waypoints are handed over as GOALs one after another
  // (ids 1, 2, ...); empty: the single goal sim.goal. sim.follow == "setpoint" also hosts
  // mmh-setpoint, and the vehicle flies its SETPOINT stream.
  std::vector<Waypoint> waypoints;
};

// One planning call as seen on PLAN_RESULT.
struct PlanCall {
  int mode = 0;
  bool ok = false;
  int reason = 0;
  double compute_ms = 0.0;
  double sim_time_s = 0.0;
};

struct PathSample {
  double t = 0.0;  // simulated seconds since the start
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double speed = 0.0;
  int mode = 0;         // mode of the trajectory being flown (plan_request_t.MODE_*), 0 = none
  double energy = 0.0;  // integral of |jerk|^2 flown so far (MissionMetrics::energy)
};

struct FlightRecord {
  sim::MissionMetrics metrics;
  std::string end_reason;  // "reached", "collided" or "timeout"
  // Why a flight that did not succeed failed, never empty for one: "refused goal: ...",
  // "unreachable: ...", "stuck: ...", "collided ..." or "timeout: ..." (failureReason). Empty
  // for a success.
  std::string failure_reason;
  std::vector<PlanCall> calls;
  std::array<int, 5> iterations{};  // planning calls per mode index
  int commits = 0, stops = 0, failed_decisions = 0;
  // FNV-1a over the encoded TRAJECTORY messages in order: equal digests mean the same committed
  // trajectories at the same times, so two builds can be shown to fly identically.
  uint64_t trajectory_digest = 14695981039346656037ull;
  std::vector<PathSample> path;  // 10 Hz
  FlightCensus census;           // stops, their causes, stalls
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;
  bool success() const { return metrics.reached && !metrics.collided; }
};

// What the flight's end and the arbiter said make of a failure (the text of
// FlightRecord::failure_reason): a collision first; then, for a timeout, the arbiter's last refusal
// of the goal, else its last "unreachable", else a long stretch without progress ("stuck", at
// least stuck_after_s), else the plain timeout with the distance left. Empty for a success.
struct FailureEvidence {
  bool reached = false, collided = false;
  double collision_time_s = 0.0;
  Eigen::Vector3d collision_position = Eigen::Vector3d::Zero();
  double sim_time_s = 0.0, distance_to_goal_m = 0.0;
  std::string rejected_detail, unreachable_detail;  // the arbiter's last, if any
  double longest_no_progress_s = 0.0, longest_no_progress_from_s = 0.0;
  double stuck_after_s = 10.0;
};
std::string failureReason(const FailureEvidence& e);

class Stack {
 public:
  explicit Stack(const StackOptions& options);
  ~Stack();
  Stack(const Stack&) = delete;
  Stack& operator=(const Stack&) = delete;

  // Publishes the goal and runs until the goal is reached, the vehicle collides, or timeout_s.
  // The first vehicle's record.
  FlightRecord fly();
  // Same for every vehicle: runs until each one has finished or timeout_s; one record per
  // vehicle. `on_second`, if set, is called after every simulated second (e.g. to sample memory).
  std::vector<FlightRecord> flyAll(const std::function<void(double sim_s)>& on_second = {});
  // Channel prefix of vehicle i (from 0).
  std::string vehiclePrefix(int i) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mmh
