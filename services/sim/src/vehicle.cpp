#include "mmh/sim/vehicle.hpp"

#include <algorithm>
#include <cmath>

namespace mmh::sim {
namespace {

double toSeconds(int64_t us) {
  return static_cast<double>(us) * 1e-6;
}

}  // namespace

Vehicle::Vehicle(const Eigen::Vector3d& start, double yaw_rad, int64_t now_utime,
                 const SimParams& params)
    : params_(params),
      heading_{params.yaw_lookahead_s, params.yaw_time_constant_s, params.max_yaw_rate_dps,
               params.yaw_lookahead_min_m},
      now_(now_utime),
      hold_(start),
      yaw_(wrapAngle(yaw_rad)) {
  state_.position = start;
}

Eigen::Quaterniond Vehicle::orientation() const {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw_, Eigen::Vector3d::UnitZ()));
}

void Vehicle::commit(std::shared_ptr<const Trajectory> trajectory, int64_t start_utime,
                     int64_t trajectory_id) {
  // The arbiter numbers its commits 1, 2, 3...: a gap means the transport lost one (a restarted
  // arbiter starts again from 1, which is no loss).
  if (last_commit_id_ > 0 && trajectory_id > last_commit_id_ + 1) {
    lost_commits_ += static_cast<int>(trajectory_id - last_commit_id_ - 1);
    follows_a_lost_commit_.insert(trajectory_id);
  }
  last_commit_id_ = trajectory_id;
  schedule_.commit(std::move(trajectory), start_utime, trajectory_id);
}

void Vehicle::followSetpoints() {
  follows_setpoints_ = true;
  schedule_.clear();
  active_.reset();
}

void Vehicle::setSetpoint(const SetpointSample& setpoint) {
  if (setpoint_ && setpoint.utime < setpoint_->utime) return;  // an older one came late
  setpoint_ = setpoint;
  active_id_ = setpoint.trajectory_id;
  if (first_utime_ < 0 && setpoint.on_trajectory) first_utime_ = std::max(setpoint.utime, now_);
}

KinematicState Vehicle::stateAt(int64_t utime) const {
  KinematicState s;
  if (!active_) {
    s.position = hold_;
    return s;
  }
  const double t = toSeconds(utime - active_start_);
  if (t >= active_->duration()) {
    // Ran out: hold the end point at rest.
    s.position = active_->position(active_->duration());
    return s;
  }
  return active_->state(std::max(0.0, t));
}

void Vehicle::flyActive(int64_t from, int64_t to, std::vector<FlownPart>* flown) const {
  if (!active_ || to <= from) return;
  const double d = active_->duration();
  const double t0 = std::clamp(toSeconds(from - active_start_), 0.0, d);
  const double t1 = std::clamp(toSeconds(to - active_start_), 0.0, d);
  if (t1 > t0 && flown) flown->push_back(FlownPart{active_, t0, t1});
}

void Vehicle::advance(int64_t now_utime, std::vector<FlownPart>* flown) {
  if (now_utime <= now_) return;
  if (follows_setpoints_) {
    advanceOnSetpoints(now_utime);
  } else {
    advanceOnTrajectory(now_utime, flown);
  }
}

void Vehicle::advanceOnTrajectory(int64_t now_utime, std::vector<FlownPart>* flown) {
  int64_t t = now_;
  while (std::optional<ScheduledTrajectory> next = schedule_.popDue(now_utime)) {
    const int64_t switch_at = std::max(next->start_utime, t);
    flyActive(t, switch_at, flown);
    const Eigen::Vector3d before = stateAt(switch_at).position;
    // Where the old trajectory was at the new one's start: a gap there is a discontinuity of the
    // trajectories themselves; a step only at switch_at comes from the commit arriving late.
    const Eigen::Vector3d at_its_start = stateAt(next->start_utime).position;
    const bool has_trajectory = next->trajectory && !next->trajectory->empty();
    const double gap_at_start =
        has_trajectory ? (next->trajectory->position(0.0) - at_its_start).norm() : 0.0;
    if (has_trajectory) {
      active_ = std::move(next->trajectory);
      active_start_ = next->start_utime;
      active_id_ = next->id;
      if (first_utime_ < 0) first_utime_ = switch_at;
    } else {
      active_.reset();
      active_id_ = next->id;
      hold_ = before;
    }
    const double step = (stateAt(switch_at).position - before).norm();
    jump_distance_ += step > kJumpM ? step : 0.0;
    const bool after_loss = follows_a_lost_commit_.erase(next->id) > 0;
    if (gap_at_start > kJumpM && after_loss) {
      ++jumps_after_loss_;
      last_jump_ = step;
    } else if (gap_at_start > kJumpM || (step > kJumpM && switch_at == next->start_utime)) {
      ++jumps_;
      last_jump_ = step;
    } else if (switch_at > next->start_utime) {
      ++late_takeovers_;
      last_lateness_s_ = 1e-6 * static_cast<double>(switch_at - next->start_utime);
      last_late_step_m_ = step;
    }
    t = switch_at;
  }
  flyActive(t, now_utime, flown);
  const double dt = toSeconds(now_utime - now_);
  now_ = now_utime;
  state_ = stateAt(now_);
  if (!active_) hold_ = state_.position;
  updateYaw(dt);
}

void Vehicle::advanceOnSetpoints(int64_t now_utime) {
  const double dt = toSeconds(now_utime - now_);
  const int64_t step_start = now_;
  now_ = now_utime;
  if (!setpoint_) return;  // nothing to track yet: hold at rest
  // The controller acts on the reference at the start of the step (causal), the error is measured
  // against the reference at its end.
  const TrackingParams& tracking = params_.tracking;
  const KinematicState before = state_;
  state_ = trackingStep(before, referenceAt(*setpoint_, step_start, tracking), dt, tracking);
  const KinematicState reference = referenceAt(*setpoint_, now_, tracking);
  model_distance_m_ += (state_.position - before.position).norm();
  const Eigen::Vector3d jerk = (state_.acceleration - before.acceleration) / dt;
  model_energy_ += jerk.squaredNorm() * dt;
  tracking_error_m_ = (state_.position - reference.position).norm();
  yaw_ = turnTowards(yaw_, setpoint_->yaw_rad, dt, heading_);
}

void Vehicle::updateYaw(double dt) {
  if (!active_ || dt <= 0.0) return;
  yaw_ =
      followHeading(yaw_, *active_, toSeconds(now_ - active_start_), state_.position, dt, heading_);
}

}  // namespace mmh::sim
