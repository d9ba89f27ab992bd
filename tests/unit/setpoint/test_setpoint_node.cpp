// The node over memq://: SETPOINT at setpoint.rate_hz from the committed TRAJECTORY, and the
// watchdog's reason in HEARTBEAT.
#include <gtest/gtest.h>

#include "mmh/common/msg_convert.hpp"
#include "setpoint_node.hpp"

namespace {

struct Listener {
  void onSetpoint(const mmh::setpoint_t& m) { setpoints.push_back(m); }
  std::vector<mmh::setpoint_t> setpoints;
};

mmh::Config defaultConfig() {
  return mmh::Config::loadFile(std::string(MMH_SOURCE_DIR) + "/deploy/config/default.yaml");
}

}  // namespace

TEST(SetpointNode, PublishesAtItsRateAndReportsTheWatchdogInHeartbeat) {
  auto lcm = mmh::openLcm("memq://");
  mmh::ServiceContext node_ctx(*lcm, "mmh-setpoint", "");
  mmh::ServiceContext test_ctx(*lcm, "test", "");
  mmh::SetpointNode node(node_ctx, defaultConfig());
  Listener l;
  test_ctx.subscribe(mmh::channels::kSetpoint, &Listener::onSetpoint, &l);
  const int64_t t0 = 1'000'000'000;
  mmh::trajectory_t traj{};
  traj.header.utime = t0;
  traj.trajectory_id = 3;
  traj.start_utime = t0;
  mmh::Piece piece;
  piece.duration = 20.0;
  piece.coeffs(0, 1) = 1.0;  // 1 m/s along x
  piece.coeffs(2, 0) = 1.2;
  mmh::toMsg(mmh::Trajectory({piece}), traj);
  test_ctx.publish(mmh::channels::kTrajectory, traj);
  while (lcm->handleTimeout(0) > 0) {
  }
  for (int i = 0; i <= 100; ++i) node.tick(t0 + i * 5'000);  // 0.5 s in 5 ms ticks
  while (lcm->handleTimeout(0) > 0) {
  }
  ASSERT_EQ(l.setpoints.size(), 51u);  // 100 Hz
  EXPECT_EQ(l.setpoints.back().trajectory_id, 3);
  EXPECT_EQ(l.setpoints.back().state, mmh::setpoint_t::STATE_TRACKING);
  EXPECT_NEAR(l.setpoints.back().position[0], 0.5, 1e-9);
  EXPECT_NEAR(l.setpoints.back().velocity[0], 1.0, 1e-9);
  EXPECT_EQ(node_ctx.state(), mmh::heartbeat_t::STATE_OK);
  // Silence: no TRAJECTORY, no arbiter HEARTBEAT for more than setpoint.watchdog_s (2.5 s).
  for (int i = 1; i <= 400; ++i) node.tick(t0 + 500'000 + i * 10'000);
  while (lcm->handleTimeout(0) > 0) {
  }
  EXPECT_EQ(node_ctx.state(), mmh::heartbeat_t::STATE_DEGRADED);
  EXPECT_EQ(node_ctx.counter("watchdog_trips"), 1);
  EXPECT_EQ(l.setpoints.back().state, mmh::setpoint_t::STATE_HOVER);
}
