#include "mmh/sim/vehicle.hpp"

#include <algorithm>
#include <cmath>

namespace mmh::sim {
namespace {

double wrapPi(double a) {
  return std::remainder(a, 2.0 * M_PI);
}

double toSeconds(int64_t us) {
  return static_cast<double>(us) * 1e-6;
}

}  // namespace

Vehicle::Vehicle(const Eigen::Vector3d& start, double yaw_rad, int64_t now_utime,
                 const SimParams& params)
    : params_(params), now_(now_utime), hold_(start), yaw_(wrapPi(yaw_rad)) {
  state_.position = start;
}

Eigen::Quaterniond Vehicle::orientation() const {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw_, Eigen::Vector3d::UnitZ()));
}

void Vehicle::commit(std::shared_ptr<const Trajectory> trajectory, int64_t start_utime,
                     int64_t trajectory_id) {
  while (!pending_.empty() && pending_.back().start_utime >= start_utime) pending_.pop_back();
  pending_.push_back(Pending{std::move(trajectory), start_utime, trajectory_id});
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
  int64_t t = now_;
  while (!pending_.empty() && pending_.front().start_utime <= now_utime) {
    Pending next = std::move(pending_.front());
    pending_.pop_front();
    const int64_t switch_at = std::max(next.start_utime, t);
    flyActive(t, switch_at, flown);
    const Eigen::Vector3d before = stateAt(switch_at).position;
    if (next.trajectory && !next.trajectory->empty()) {
      active_ = std::move(next.trajectory);
      active_start_ = next.start_utime;
      active_id_ = next.id;
      if (first_utime_ < 0) first_utime_ = switch_at;
    } else {
      active_.reset();
      active_id_ = next.id;
      hold_ = before;
    }
    last_jump_ = (stateAt(switch_at).position - before).norm();
    if (last_jump_ > 1e-3) {
      ++jumps_;
      jump_distance_ += last_jump_;
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

void Vehicle::updateYaw(double dt) {
  if (!active_ || dt <= 0.0) return;
  // Direction of flight: towards the point yaw_lookahead_s ahead on the trajectory.
  const double t = toSeconds(now_ - active_start_);
  const double ahead = std::min(t + params_.yaw_lookahead_s, active_->duration());
  const Eigen::Vector3d look = active_->position(std::max(0.0, ahead)) - state_.position;
  if (look.head<2>().norm() < 0.05) return;  // hovering or nearly there: keep the heading
  const double error = wrapPi(std::atan2(look.y(), look.x()) - yaw_);
  const double max_rate = params_.max_yaw_rate_dps * M_PI / 180.0;
  double change = params_.yaw_time_constant_s > 0.0
                      ? error * std::min(1.0, dt / params_.yaw_time_constant_s)
                      : error;
  change = std::clamp(change, -max_rate * dt, max_rate * dt);
  yaw_ = wrapPi(yaw_ + change);
}

}  // namespace mmh::sim
