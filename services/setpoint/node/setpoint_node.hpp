// The trajectory server as an LCM node: TRAJECTORY, the arbiter's HEARTBEAT and ODOMETRY in,
// SETPOINT out at setpoint.rate_hz. No thread and no wall clock: tick(now) publishes what is due
// by `now` (mmh-stack calls it after every lock-step; main.cpp on a timer, with the message clock
// carried forward by the wall clock between messages).
#pragma once

#include <cstdint>

#include "mmh/common/config.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/heartbeat_t.hpp"
#include "mmh/odometry_t.hpp"
#include "mmh/setpoint/setpoint_server.hpp"
#include "mmh/setpoint_t.hpp"
#include "mmh/trajectory_t.hpp"

namespace mmh {

class SetpointNode {
 public:
  SetpointNode(ServiceContext& ctx, const Config& config);
  SetpointNode(ServiceContext& ctx, const setpoint::Params& params);

  // Publishes the SETPOINT due by `now` (message-clock time; at most one per call).
  void tick(int64_t now);
  const setpoint::SetpointServer& server() const { return server_; }

  static setpoint_t toMessage(const setpoint::Setpoint& sp);

 private:
  void onTrajectory(const trajectory_t& msg);
  void onHeartbeat(const heartbeat_t& msg);
  void onOdometry(const odometry_t& msg);
  void report();  // HEARTBEAT state and counters

  ServiceContext& ctx_;
  setpoint::SetpointServer server_;
  int64_t period_us_;
  int64_t next_due_ = 0;
  bool was_tripped_ = false;
};

}  // namespace mmh
