#include "mmh/setpoint/setpoint_server.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mmh/common/heading.hpp"
#include "mmh/common/stopping_trajectory.hpp"

namespace mmh::setpoint {
namespace {

double seconds(int64_t us) {
  return static_cast<double>(us) * 1e-6;
}

constexpr double kJumpM = 1e-3;  // a take-over farther than this from the setpoint is a jump

}  // namespace

const char* toString(State state) {
  switch (state) {
    case State::kHold:
      return "hold";
    case State::kTracking:
      return "tracking";
    case State::kEnd:
      return "end";
    case State::kBraking:
      return "braking";
    case State::kHover:
      return "hover";
  }
  return "?";
}

SetpointServer::SetpointServer(const Params& params) : params_(params) {}

void SetpointServer::commit(std::shared_ptr<const Trajectory> trajectory, int64_t start_utime,
                            int64_t id, int64_t now) {
  ++counters_.trajectories;
  last_alive_ = std::max(last_alive_.value_or(now), now);
  if (tripped_) {
    // The planner is back: its trajectory replaces the brake at its start time.
    tripped_ = false;
    watchdog_reason_.clear();
  }
  schedule_.commit(std::move(trajectory), start_utime, id);
}

void SetpointServer::arbiterAlive(int64_t now) {
  last_alive_ = std::max(last_alive_.value_or(now), now);
}

void SetpointServer::vehicleAt(const Eigen::Vector3d& position, double yaw_rad) {
  if (hasTrajectory() || hold_) return;
  hold_ = position;
  yaw_ = wrapAngle(yaw_rad);
}

KinematicState SetpointServer::followedAt(int64_t utime, Eigen::Vector3d* jerk) const {
  *jerk = Eigen::Vector3d::Zero();
  KinematicState s;
  if (!path_) {
    s.position = hold_.value_or(Eigen::Vector3d::Zero());
    return s;
  }
  const double t = seconds(utime - path_start_);
  if (t >= path_->duration()) {
    s.position = path_->position(path_->duration());  // ran out: its end, at rest
    return s;
  }
  const double tc = std::max(0.0, t);
  *jerk = path_->derivative(3, tc);
  return path_->state(tc);
}

void SetpointServer::takeOverDue(int64_t utime) {
  while (std::optional<ScheduledTrajectory> next = schedule_.popDue(utime)) {
    const int64_t switch_at = std::max(next->start_utime, last_utime_.value_or(next->start_utime));
    Eigen::Vector3d unused;
    const bool had_setpoint = path_ || hold_;  // the first take-over starts from nothing
    const Eigen::Vector3d before = followedAt(switch_at, &unused).position;
    braking_ = false;
    path_id_ = next->id;
    if (next->trajectory && !next->trajectory->empty()) {
      path_ = std::move(next->trajectory);
      path_start_ = next->start_utime;
    } else {
      path_.reset();
      hold_ = before;
    }
    ++counters_.switches;
    if (had_setpoint && (followedAt(switch_at, &unused).position - before).norm() > kJumpM) {
      ++counters_.jumps;
    }
  }
}

void SetpointServer::trip(int64_t utime) {
  tripped_ = true;
  ++counters_.watchdog_trips;
  schedule_.clear();
  const double silent_s = seconds(utime - *last_alive_);
  std::ostringstream why;
  why.precision(3);
  why << "watchdog: no TRAJECTORY and no mmh-arbiter HEARTBEAT for " << silent_s
      << " s (setpoint.watchdog_s " << params_.watchdog_s << " s): ";
  const bool moving =
      path_ && seconds(utime - path_start_) < path_->duration() && path_->duration() > 0.0;
  if (moving) {
    // Brake along the path being flown (an avoidance under way is kept), |a| <= a_max.
    const double t0 = std::max(0.0, seconds(utime - path_start_));
    path_ = std::make_shared<const Trajectory>(
        makeStoppingTrajectory(*path_, t0, params_.max_acc_mps2, params_.max_vel_mps));
    path_start_ = utime;
    braking_ = true;
    why << "braking to a hover";
  } else {
    why << "hovering";
  }
  Eigen::Vector3d unused;
  const Eigen::Vector3d hover =
      path_ ? path_->position(path_->duration()) : followedAt(utime, &unused).position;
  why << " at (" << hover.x() << ", " << hover.y() << ", " << hover.z() << ")";
  watchdog_reason_ = why.str();
}

std::optional<Setpoint> SetpointServer::sample(int64_t utime) {
  if (last_utime_) utime = std::max(utime, *last_utime_);
  // Armed by the first trajectory: before it there is nothing to brake from.
  if (!tripped_ && hasTrajectory() && seconds(utime - *last_alive_) > params_.watchdog_s) {
    trip(utime);
  }
  if (!tripped_) takeOverDue(utime);
  if (!path_ && !hold_) return std::nullopt;
  const double dt = last_utime_ ? seconds(utime - *last_utime_) : 0.0;
  last_utime_ = utime;

  Setpoint sp;
  sp.utime = utime;
  sp.trajectory_id = path_id_;
  sp.kinematics = followedAt(utime, &sp.jerk);
  const bool on_path = path_ && seconds(utime - path_start_) < path_->duration();
  if (!path_) {
    sp.state = tripped_ ? State::kHover : State::kHold;
  } else if (braking_) {
    sp.state = on_path ? State::kBraking : State::kHover;
  } else if (tripped_) {
    sp.state = State::kHover;  // tripped while holding the end of a trajectory
  } else {
    sp.state = on_path ? State::kTracking : State::kEnd;
  }
  const double before = yaw_;
  if (on_path && dt > 0.0) {
    yaw_ = followHeading(yaw_, *path_, std::max(0.0, seconds(utime - path_start_)),
                         sp.kinematics.position, dt, params_.heading);
  }
  sp.yaw_rad = yaw_;
  sp.yaw_rate_radps = dt > 0.0 ? wrapAngle(yaw_ - before) / dt : 0.0;
  return sp;
}

}  // namespace mmh::setpoint
