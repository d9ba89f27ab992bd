// The simulated vehicle. By default it follows the committed trajectory exactly (as the paper's
// simulator does), holds its position with zero velocity when it has none or when it ran out,
// and takes a new trajectory over at that trajectory's start time (the old one is flown until
// then). With followSetpoints() it flies the SETPOINT stream through a tracking model instead
// (tracking_model.hpp), as a flight controller would. Yaw follows the direction of flight,
// smoothed and rate-limited, so the forward camera looks where the vehicle goes.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <vector>

#include "mmh/common/heading.hpp"
#include "mmh/common/trajectory.hpp"
#include "mmh/common/trajectory_schedule.hpp"
#include "mmh/sim/sim_params.hpp"
#include "mmh/sim/tracking_model.hpp"

namespace mmh::sim {

// A part of a trajectory that was flown, in the trajectory's own time (seconds from its start).
struct FlownPart {
  std::shared_ptr<const Trajectory> trajectory;
  double t0 = 0.0, t1 = 0.0;
};

class Vehicle {
 public:
  Vehicle(const Eigen::Vector3d& start, double yaw_rad, int64_t now_utime, const SimParams& params);

  // Queues a committed trajectory that takes over at start_utime (at the next step if that time
  // has passed). A later commit replaces queued ones that would start at or after its own start.
  // An empty trajectory means: hold the position reached at start_utime.
  void commit(std::shared_ptr<const Trajectory> trajectory, int64_t start_utime,
              int64_t trajectory_id);

  // From now on fly the setpoints given to setSetpoint() through the tracking model (and ignore
  // commit()). Until the first setpoint the vehicle holds where it is.
  void followSetpoints();
  bool followsSetpoints() const { return follows_setpoints_; }
  void setSetpoint(const SetpointSample& setpoint);

  // Advances to now_utime, appending the trajectory parts flown since the last call to `flown`
  // (none while following setpoints: see modelDistance, modelEnergy).
  void advance(int64_t now_utime, std::vector<FlownPart>* flown);

  int64_t nowUtime() const { return now_; }
  const KinematicState& state() const { return state_; }
  double yaw() const { return yaw_; }
  Eigen::Quaterniond orientation() const;
  int64_t activeTrajectoryId() const { return active_id_; }
  bool hasTrajectory() const { return active_ != nullptr; }
  // Start time of the first trajectory that took over (following setpoints: of the first setpoint
  // on a trajectory); -1 before that.
  int64_t firstTrajectoryUtime() const { return first_utime_; }
  // A new trajectory that did not start where the old one was at its start time (more than 1 mm
  // away): the vehicle jumps, since it follows the trajectory exactly. A planner or arbiter bug.
  int jumps() const { return jumps_; }
  double lastJump() const { return last_jump_; }
  // A trajectory that arrived after its start time (the commit was delivered late: a loaded
  // computer or network) is taken over at the next step, where it may be a little away from the
  // old one; a real vehicle's controller absorbs such a step. Counted apart from jumps.
  int lateTakeovers() const { return late_takeovers_; }
  double lastLatenessS() const { return last_lateness_s_; }
  double lastLateStepM() const { return last_late_step_m_; }
  // Commits the transport lost (a gap in the arbiter's trajectory ids), and the jumps onto the
  // commit after such a gap: it continues the lost one, not what the vehicle flies. Counted apart.
  int lostCommits() const { return lost_commits_; }
  int jumpsAfterLoss() const { return jumps_after_loss_; }
  // Sum of the position steps of all kinds, for the distance flown.
  double jumpDistance() const { return jump_distance_; }
  // Following setpoints: the arc length flown and the integral of |jerk|^2 dt so far, and the
  // distance from the vehicle to the reference at the last step (nullopt before a setpoint).
  double modelDistance() const { return model_distance_m_; }
  double modelEnergy() const { return model_energy_; }
  std::optional<double> trackingError() const { return tracking_error_m_; }

 private:
  KinematicState stateAt(int64_t utime) const;
  void flyActive(int64_t from, int64_t to, std::vector<FlownPart>* flown) const;
  void advanceOnTrajectory(int64_t now_utime, std::vector<FlownPart>* flown);
  void advanceOnSetpoints(int64_t now_utime);
  void updateYaw(double dt);

  SimParams params_;
  HeadingParams heading_;
  int64_t now_;
  KinematicState state_;
  Eigen::Vector3d hold_;  // position held without a trajectory
  std::shared_ptr<const Trajectory> active_;
  int64_t active_start_ = 0, active_id_ = 0;
  TrajectorySchedule schedule_;
  int64_t first_utime_ = -1;
  static constexpr double kJumpM = 1e-3;
  int jumps_ = 0, late_takeovers_ = 0, lost_commits_ = 0, jumps_after_loss_ = 0;
  int64_t last_commit_id_ = 0;
  std::set<int64_t> follows_a_lost_commit_;
  double jump_distance_ = 0.0, last_jump_ = 0.0;
  double last_lateness_s_ = 0.0, last_late_step_m_ = 0.0;
  double yaw_ = 0.0;
  // Following setpoints.
  bool follows_setpoints_ = false;
  std::optional<SetpointSample> setpoint_;
  double model_distance_m_ = 0.0, model_energy_ = 0.0;
  std::optional<double> tracking_error_m_;
};

}  // namespace mmh::sim
