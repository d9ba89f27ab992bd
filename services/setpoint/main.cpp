// mmh-setpoint: the trajectory server as a process. Samples the committed TRAJECTORY into
// SETPOINT at setpoint.rate_hz for a flight controller (docs/setpoint.md). Between messages its
// clock is the newest message time carried forward by the wall clock, so the setpoints keep
// their rate, and its watchdog sees the planner fall silent, even when every input stops.
#include <algorithm>
#include <iostream>

#include "mmh/common/node_options.hpp"
#include "setpoint_node.hpp"

int main(int argc, char** argv) {
  mmh::NodeOptions options;
  mmh::ArgParser parser("mmh-setpoint",
                        "Trajectory server: samples the committed TRAJECTORY into SETPOINT "
                        "(position, velocity, acceleration, jerk, yaw, yaw rate) at "
                        "setpoint.rate_hz; brakes to a hover when the planner falls silent.");
  mmh::addNodeOptions(parser, &options);
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  mmh::setLogServiceName("mmh-setpoint");
  try {
    const mmh::Config config = mmh::loadNodeConfig(options);
    const mmh::setpoint::Params params = mmh::setpoint::loadParams(config);
    auto lcm = mmh::openLcm(options.lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-setpoint", options.prefix);
    mmh::SetpointNode node(ctx, params);
    mmh::installStopHandlers();
    ctx.publishHeartbeat();
    const auto period_us = static_cast<int64_t>(1e6 / params.rate_hz);
    int64_t clock_seen = 0, clock_seen_wall = mmh::wallTimeUs(), last_tick = 0;
    int64_t next_wall = mmh::wallTimeUs();
    while (!mmh::stopRequested()) {
      const int64_t wait_ms = std::clamp<int64_t>((next_wall - mmh::wallTimeUs()) / 1000, 0, 100);
      if (lcm->handleTimeout(static_cast<int>(wait_ms)) < 0) {
        if (mmh::stopRequested()) break;
        mmh::logError("mmh-setpoint: LCM handle failed; stopping");
        return 1;
      }
      const int64_t wall = mmh::wallTimeUs();
      if (ctx.clock().now() != clock_seen) {
        clock_seen = ctx.clock().now();
        clock_seen_wall = wall;
      }
      ctx.maybePublishHeartbeat(wall);
      if (wall < next_wall) continue;
      next_wall = std::max(next_wall + period_us, wall - period_us);
      if (clock_seen == 0) continue;  // no message yet: no time to sample at
      last_tick = std::max(last_tick, clock_seen + (wall - clock_seen_wall));
      node.tick(last_tick);
    }
    ctx.setState(mmh::heartbeat_t::STATE_STOPPING, "stopped");
    ctx.publishHeartbeat();
    return 0;
  } catch (const mmh::ConfigError& e) {
    std::cerr << "mmh-setpoint: " << e.what() << "\n";
    return 1;
  } catch (const mmh::LcmError& e) {
    std::cerr << "mmh-setpoint: " << e.what() << "\n";
    return 1;
  }
}
