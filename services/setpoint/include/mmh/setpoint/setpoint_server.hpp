// The trajectory server: turns the committed trajectories into the fixed-rate setpoints a flight
// controller takes (position, velocity, acceleration, jerk, yaw, yaw rate). A new trajectory
// takes over exactly at its start time, so the setpoints go on without a jump (the arbiter starts
// every trajectory in the state of the committed one at that time); at the end of a trajectory
// its end point is held at rest. Its watchdog: when neither a TRAJECTORY nor an arbiter HEARTBEAT
// came for watchdog_s, the planner is gone, and the server brakes along the path it follows to a
// hover within a_max, until a new TRAJECTORY arrives. No LCM here: the node feeds it and
// publishes what it samples; every time is the message clock (microseconds).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "mmh/common/trajectory.hpp"
#include "mmh/common/trajectory_schedule.hpp"
#include "mmh/setpoint/setpoint_params.hpp"

namespace mmh::setpoint {

// setpoint_t.STATE_*.
enum class State : int8_t { kHold = 0, kTracking = 1, kEnd = 2, kBraking = 3, kHover = 4 };
const char* toString(State state);

struct Setpoint {
  int64_t utime = 0;
  int64_t trajectory_id = 0;  // the trajectory followed (braking: the one braked from)
  State state = State::kHold;
  KinematicState kinematics;
  Eigen::Vector3d jerk = Eigen::Vector3d::Zero();
  double yaw_rad = 0.0;
  double yaw_rate_radps = 0.0;
};

struct ServerCounters {
  int trajectories = 0;  // commits received
  int switches = 0;      // trajectories that took over
  int jumps = 0;         // ... not where the setpoint was (more than 1 mm away)
  int watchdog_trips = 0;
};

class SetpointServer {
 public:
  explicit SetpointServer(const Params& params);

  // A committed trajectory, received at `now`: it takes over at start_utime (at the next sample
  // if that has passed). Empty: hold where the setpoint is at start_utime. Ends a watchdog brake.
  void commit(std::shared_ptr<const Trajectory> trajectory, int64_t start_utime, int64_t id,
              int64_t now);
  // A HEARTBEAT of the arbiter at `now`.
  void arbiterAlive(int64_t now);
  // Where the vehicle is (ODOMETRY): held, facing `yaw_rad`, until the first trajectory.
  void vehicleAt(const Eigen::Vector3d& position, double yaw_rad);

  // The setpoint at `utime` (never earlier than the one before). nullopt while neither a
  // trajectory nor the vehicle's position is known.
  std::optional<Setpoint> sample(int64_t utime);

  bool watchdogTripped() const { return tripped_; }
  // Why the watchdog tripped (empty while it has not).
  const std::string& watchdogReason() const { return watchdog_reason_; }
  bool hasTrajectory() const { return counters_.trajectories > 0; }
  const ServerCounters& counters() const { return counters_; }
  const Params& params() const { return params_; }

 private:
  // Position, velocity, acceleration and jerk of what is followed at utime.
  KinematicState followedAt(int64_t utime, Eigen::Vector3d* jerk) const;
  void takeOverDue(int64_t utime);
  void trip(int64_t utime);

  Params params_;
  TrajectorySchedule schedule_;
  std::shared_ptr<const Trajectory> path_;  // followed now; null: hold hold_
  int64_t path_start_ = 0, path_id_ = 0;
  std::optional<Eigen::Vector3d> hold_;
  bool braking_ = false;  // path_ is the watchdog's brake
  bool tripped_ = false;
  std::string watchdog_reason_;
  std::optional<int64_t> last_alive_;
  std::optional<int64_t> last_utime_;
  double yaw_ = 0.0;
  ServerCounters counters_;
};

}  // namespace mmh::setpoint
