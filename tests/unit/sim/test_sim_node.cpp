// SimNode over LCM's in-process memq:// provider, as mmh-stack uses it: ODOMETRY every step,
// POINTCLOUD at 15 Hz, MISSION_STATUS; TRAJECTORY is followed, GOAL sets the mission goal.
#include <gtest/gtest.h>

#include "mmh/common/msg_convert.hpp"
#include "sim_node.hpp"
#include "traj_helpers.hpp"

using Eigen::Vector3d;

namespace {

mmh::Config testConfig() {
  return mmh::Config::loadFile(std::string(MMH_SOURCE_DIR) + "/deploy/config/default.yaml");
}

struct Listener {
  void onOdometry(const mmh::odometry_t& m) { odometry.push_back(m); }
  void onCloud(const mmh::pointcloud_t& m) { clouds.push_back(m); }
  void onStatus(const mmh::mission_status_t& m) { statuses.push_back(m); }
  std::vector<mmh::odometry_t> odometry;
  std::vector<mmh::pointcloud_t> clouds;
  std::vector<mmh::mission_status_t> statuses;
};

}  // namespace

TEST(SimNode, PublishesAndFollowsInLockStep) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  mmh::ServiceContext sim_ctx(lcm, "mmh-sim", "");
  mmh::ServiceContext test_ctx(lcm, "test", "");
  mmh::SimOptions options;
  options.density_per_m2 = 0.1;
  mmh::SimNode sim(sim_ctx, testConfig(), options);
  Listener listener;
  test_ctx.subscribe(mmh::channels::kOdometry, &Listener::onOdometry, &listener);
  test_ctx.subscribe(mmh::channels::kPointcloud, &Listener::onCloud, &listener);
  test_ctx.subscribe(mmh::channels::kMissionStatus, &Listener::onStatus, &listener);

  // A goal and a trajectory, as the arbiter would send them.
  mmh::goal_t goal{};
  goal.header.utime = sim.nowUtime();
  goal.goal_id = 5;
  mmh::fromVec3(options.start + Vector3d(1.0, 0, 0), goal.position);
  test_ctx.publish(mmh::channels::kGoal, goal);
  auto traj = mmh::test::minJerkTraj(options.start, options.start + Vector3d(1.0, 0, 0), 2.0);
  mmh::trajectory_t msg{};
  msg.header.utime = sim.nowUtime();
  msg.trajectory_id = 9;
  msg.start_utime = sim.nowUtime() + 100'000;
  mmh::toMsg(*traj, msg);
  test_ctx.publish(mmh::channels::kTrajectory, msg);
  const int64_t start_utime = msg.start_utime;
  while (lcm.handleTimeout(0) > 0) {
  }
  for (int i = 0; i < 300 && !sim.finished(); ++i) {
    sim.step();
    while (lcm.handleTimeout(0) > 0) {
    }
  }
  EXPECT_TRUE(sim.finished());
  EXPECT_TRUE(sim.metrics().reached);
  EXPECT_EQ(sim.metrics().goal_id, 5);
  ASSERT_FALSE(listener.odometry.empty());
  // ODOMETRY every step, following the trajectory exactly, orientation along the flight.
  int64_t previous = 0;
  for (const auto& o : listener.odometry) {
    EXPECT_EQ(o.header.utime - previous, previous ? 10'000 : o.header.utime);
    previous = o.header.utime;
    const double t = (o.header.utime - start_utime) * 1e-6;
    if (t >= 0 && t <= 2.0) {
      EXPECT_NEAR((mmh::toVec3(o.position) - traj->position(t)).norm(), 0.0, 1e-9);
      EXPECT_NEAR((mmh::toVec3(o.velocity) - traj->velocity(t)).norm(), 0.0, 1e-9);
    }
  }
  EXPECT_NEAR(listener.odometry.back().orientation[0], 1.0, 1e-6);  // facing +x
  // POINTCLOUD at 15 Hz with the sensor pose; MISSION_STATUS with the goal from GOAL.
  const double seconds = listener.odometry.size() * 0.01;
  EXPECT_NEAR(listener.clouds.size(), 15.0 * seconds, 1.5);
  EXPECT_EQ(listener.clouds.front().sensor_kind, mmh::pointcloud_t::SENSOR_DEPTH);
  EXPECT_FLOAT_EQ(listener.clouds.front().max_range_m, 4.5f);
  EXPECT_EQ(listener.clouds.front().num_coords, 3 * 160 * 120);
  ASSERT_FALSE(listener.statuses.empty());
  const auto& last = listener.statuses.back();
  EXPECT_TRUE(last.reached);
  EXPECT_FALSE(last.collided);
  EXPECT_NEAR(last.goal[0], options.start.x() + 1.0, 1e-12);
  EXPECT_GT(last.flight_time_s, 1.0);
  EXPECT_NEAR(last.distance_m, 0.7, 0.05);  // arrival within 0.3 m of the 1 m goal

  // A trajectory that starts 2 m away from the vehicle: followed (exactly), but the jump is
  // counted and logged.
  auto elsewhere = mmh::test::line(options.start + Vector3d(1.0, 2.0, 0), Vector3d::Zero(), 1.0);
  msg.trajectory_id = 10;
  msg.header.utime = sim.nowUtime();
  msg.start_utime = sim.nowUtime() + 20'000;
  mmh::toMsg(*elsewhere, msg);
  test_ctx.publish(mmh::channels::kTrajectory, msg);
  for (int i = 0; i < 5; ++i) {
    while (lcm.handleTimeout(0) > 0) {
    }
    sim.step();
  }
  EXPECT_EQ(sim_ctx.counter("trajectory_jumps"), 1);
  EXPECT_NEAR((sim.simulator().vehicle().state().position - elsewhere->position(0)).norm(), 0.0,
              1e-12);
}

TEST(SimNode, BadConfigOrOptionsFailAtStartUp) {
  lcm::LCM lcm("memq://");
  mmh::ServiceContext ctx(lcm, "mmh-sim", "");
  mmh::SimOptions options;
  options.sensor = "sonar";
  EXPECT_THROW(mmh::SimNode(ctx, testConfig(), options), std::runtime_error);
  const mmh::Config bad = mmh::Config::fromString("sim: {step_s: 5.0}\n");
  EXPECT_THROW(mmh::SimNode(ctx, bad, mmh::SimOptions{}), mmh::ConfigError);
}
