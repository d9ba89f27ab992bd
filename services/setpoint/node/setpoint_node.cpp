#include "setpoint_node.hpp"

#include <cmath>

#include "mmh/common/msg_convert.hpp"

namespace mmh {

SetpointNode::SetpointNode(ServiceContext& ctx, const Config& config)
    : SetpointNode(ctx, setpoint::loadParams(config)) {}

SetpointNode::SetpointNode(ServiceContext& ctx, const setpoint::Params& params)
    : ctx_(ctx),
      server_(params),
      period_us_(std::max<int64_t>(1, std::llround(1e6 / params.rate_hz))) {
  ctx_.subscribe(channels::kTrajectory, &SetpointNode::onTrajectory, this);
  ctx_.subscribe(channels::kHeartbeat, &SetpointNode::onHeartbeat, this);
  ctx_.subscribe(channels::kOdometry, &SetpointNode::onOdometry, this);
  ctx_.setState(heartbeat_t::STATE_DEGRADED, "waiting for TRAJECTORY");
}

void SetpointNode::onTrajectory(const trajectory_t& msg) {
  auto trajectory = std::make_shared<const Trajectory>(fromMsg(msg));
  if (!trajectory->empty() && !trajectory->isFinite()) {
    ctx_.reject("rejected_trajectory", "TRAJECTORY " + std::to_string(msg.trajectory_id) +
                                           " has non-finite or non-positive pieces");
    return;
  }
  if (msg.start_utime < ctx_.clock().now()) ctx_.increment("trajectory_late");
  server_.commit(std::move(trajectory), msg.start_utime, msg.trajectory_id, ctx_.clock().now());
  report();
}

void SetpointNode::onHeartbeat(const heartbeat_t& msg) {
  if (msg.service == "mmh-arbiter") server_.arbiterAlive(ctx_.clock().now());
}

void SetpointNode::onOdometry(const odometry_t& msg) {
  // Yaw of the body's x axis from the quaternion (w, x, y, z).
  const double* q = msg.orientation;
  const double yaw =
      std::atan2(2.0 * (q[0] * q[3] + q[1] * q[2]), 1.0 - 2.0 * (q[2] * q[2] + q[3] * q[3]));
  server_.vehicleAt(toVec3(msg.position), yaw);
}

setpoint_t SetpointNode::toMessage(const setpoint::Setpoint& sp) {
  setpoint_t msg{};
  msg.header.utime = sp.utime;
  msg.trajectory_id = sp.trajectory_id;
  msg.state = static_cast<int8_t>(sp.state);
  fromVec3(sp.kinematics.position, msg.position);
  fromVec3(sp.kinematics.velocity, msg.velocity);
  fromVec3(sp.kinematics.acceleration, msg.acceleration);
  fromVec3(sp.jerk, msg.jerk);
  msg.yaw_rad = sp.yaw_rad;
  msg.yaw_rate_radps = sp.yaw_rate_radps;
  return msg;
}

void SetpointNode::tick(int64_t now) {
  if (now <= 0 || now < next_due_) return;
  next_due_ =
      next_due_ == 0 || now - next_due_ >= period_us_ ? now + period_us_ : next_due_ + period_us_;
  const std::optional<setpoint::Setpoint> sp = server_.sample(now);
  report();
  if (!sp) return;
  setpoint_t msg = toMessage(*sp);
  ctx_.publish(channels::kSetpoint, msg);
}

void SetpointNode::report() {
  const setpoint::ServerCounters& n = server_.counters();
  ctx_.setCounter("trajectories_received", n.trajectories);
  ctx_.setCounter("trajectory_switches", n.switches);
  ctx_.setCounter("trajectory_jumps", n.jumps);
  ctx_.setCounter("watchdog_trips", n.watchdog_trips);
  if (server_.watchdogTripped()) {
    if (!was_tripped_) logWarn("mmh-setpoint: " + server_.watchdogReason());
    ctx_.setState(heartbeat_t::STATE_DEGRADED, server_.watchdogReason());
  } else if (server_.hasTrajectory()) {
    if (was_tripped_) logInfo("mmh-setpoint: a TRAJECTORY came: following it again");
    ctx_.setState(heartbeat_t::STATE_OK, "");
  }
  was_tripped_ = server_.watchdogTripped();
}

}  // namespace mmh
