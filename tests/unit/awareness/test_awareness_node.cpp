// The awareness node over memq:// (in-process LCM): when it answers, what it answers, and what it
// counts when it cannot answer.
#include <gtest/gtest.h>

#include <cmath>

#include "awareness_node.hpp"
#include "mmh/awareness_t.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/heartbeat_t.hpp"

using Eigen::Vector3d;
using Eigen::Vector3i;

namespace {

const char* kConfig = R"(
map: {inflation_m: 0.3}
awareness: {sensor_range_m: 4.5, narrow_probe_dist_m: 0.8}
)";

struct Sink {
  void onAwareness(const mmh::awareness_t& m) { got.push_back(m); }
  void onHeartbeat(const mmh::heartbeat_t& m) { heartbeats.push_back(m); }
  std::vector<mmh::awareness_t> got;
  std::vector<mmh::heartbeat_t> heartbeats;
};

// 10 x 10 x 3 m free window at 0.1 m starting at (0, -5, 0), with optional pillars.
mmh::VoxelGrid window(const std::vector<Vector3d>& pillars = {}) {
  mmh::VoxelGrid g(0.1, Vector3i(0, -50, 0), Vector3i(100, 100, 30));
  for (int64_t i = 0; i < g.numCells(); ++i) {
    const Vector3d c = g.centerOfLocal(g.localFromLinear(i));
    bool occupied = false;
    for (const Vector3d& p : pillars)  // (x, y, radius)
      occupied = occupied || std::hypot(c.x() - p.x(), c.y() - p.y()) <= p.z();
    g.setLinear(i, occupied ? mmh::Occupancy::kOccupied : mmh::Occupancy::kFree);
  }
  return g;
}

class AwarenessNodeTest : public ::testing::Test {
 protected:
  AwarenessNodeTest()
      : lcm_(mmh::openLcm("memq://")),
        node_ctx_(*lcm_, "mmh-awareness", "T_"),
        test_ctx_(*lcm_, "test", "T_"),
        node_(node_ctx_, mmh::Config::fromString(kConfig)) {
    test_ctx_.subscribe(mmh::channels::kAwareness, &Sink::onAwareness, &sink_);
    test_ctx_.subscribe(mmh::channels::kHeartbeat, &Sink::onHeartbeat, &sink_);
  }

  void drain() {
    while (lcm_->handleTimeout(0) > 0) {
    }
  }
  void sendMap(mmh::local_map_t m, int64_t utime) {
    m.header.utime = utime;
    test_ctx_.publish(mmh::channels::kLocalMap, m);
    drain();
  }
  void sendPose(const Vector3d& p, int64_t utime) {
    mmh::odometry_t m{};
    m.header.utime = utime;
    m.position[0] = p.x();
    m.position[1] = p.y();
    m.position[2] = p.z();
    m.orientation[0] = 1.0;
    test_ctx_.publish(mmh::channels::kOdometry, m);
    drain();
  }
  void sendGoal(int64_t id, const Vector3d& p, int64_t utime) {
    mmh::goal_t m{};
    m.header.utime = utime;
    m.goal_id = id;
    m.position[0] = p.x();
    m.position[1] = p.y();
    m.position[2] = p.z();
    test_ctx_.publish(mmh::channels::kGoal, m);
    drain();
  }

  std::unique_ptr<lcm::LCM> lcm_;
  mmh::ServiceContext node_ctx_, test_ctx_;
  mmh::AwarenessNode node_;
  Sink sink_;
};

}  // namespace

TEST_F(AwarenessNodeTest, NothingWithoutMapPoseAndGoalAndTheReasonIsCounted) {
  sendGoal(1, Vector3d(9, 0, 1.5), 1000);  // no map, no pose
  EXPECT_EQ(node_ctx_.counter("skipped_no_map"), 1);
  sendMap(mmh::makeKeyframe(window(), 1), 2000);  // map + goal, no pose
  EXPECT_EQ(node_ctx_.counter("skipped_no_pose"), 1);
  EXPECT_TRUE(sink_.got.empty());
  EXPECT_EQ(node_ctx_.state(), mmh::heartbeat_t::STATE_DEGRADED);
  // The counters travel in HEARTBEAT.
  node_ctx_.publishHeartbeat();
  drain();
  ASSERT_FALSE(sink_.heartbeats.empty());
  const auto& hb = sink_.heartbeats.back();
  bool found = false;
  for (int i = 0; i < hb.num_counters; ++i)
    found = found || (hb.counter_names[i] == "skipped_no_pose" && hb.counter_values[i] == 1);
  EXPECT_TRUE(found);
  EXPECT_EQ(hb.state, mmh::heartbeat_t::STATE_DEGRADED);
}

TEST_F(AwarenessNodeTest, NoGoalYetIsCounted) {
  sendPose(Vector3d(1, 0, 1.5), 1000);
  sendMap(mmh::makeKeyframe(window(), 1), 2000);
  EXPECT_EQ(node_ctx_.counter("skipped_no_goal"), 1);
  EXPECT_TRUE(sink_.got.empty());
}

TEST_F(AwarenessNodeTest, AnswersOnEveryMapUpdateAndEveryGoalChange) {
  sendPose(Vector3d(1, 0, 1.5), 1000);
  sendGoal(7, Vector3d(20, 0, 1.5), 1500);
  EXPECT_TRUE(sink_.got.empty());  // no map yet
  mmh::VoxelGrid g = window();
  sendMap(mmh::makeKeyframe(g, 1), 2000);
  ASSERT_EQ(sink_.got.size(), 1u);
  const mmh::awareness_t& a = sink_.got[0];
  EXPECT_TRUE(a.safe);
  EXPECT_EQ(a.reason, mmh::awareness_t::REASON_CLEAR);
  EXPECT_EQ(a.map_seq, 1);
  EXPECT_EQ(a.goal_id, 7);
  EXPECT_NEAR(a.ray_end[0], 5.5, 1e-9);  // clipped to the 4.5 m sensor range
  EXPECT_NEAR(a.goal[0], 20.0, 1e-9);
  EXPECT_NEAR(a.position[0], 1.0, 1e-9);
  EXPECT_FALSE(a.has_blocked_point);
  EXPECT_GT(a.compute_ns, 0);
  EXPECT_EQ(a.header.source, "mmh-awareness");
  EXPECT_EQ(node_ctx_.state(), mmh::heartbeat_t::STATE_OK);

  // A delta puts a pillar on the ray: BLOCKED on the new map sequence.
  std::vector<mmh::CellChange> changes;
  const mmh::VoxelGrid with_pillar = window({Vector3d(3.0, 0.0, 0.3)});
  for (int64_t i = 0; i < g.numCells(); ++i)
    if (with_pillar.atLinear(i) != g.atLinear(i)) changes.emplace_back(i, with_pillar.atLinear(i));
  sendMap(mmh::makeDelta(with_pillar, 2, changes), 3000);
  ASSERT_EQ(sink_.got.size(), 2u);
  EXPECT_FALSE(sink_.got[1].safe);
  EXPECT_EQ(sink_.got[1].reason, mmh::awareness_t::REASON_BLOCKED);
  EXPECT_EQ(sink_.got[1].map_seq, 2);
  ASSERT_TRUE(sink_.got[1].has_blocked_point);
  EXPECT_NEAR(sink_.got[1].first_blocked[0], 2.4, 0.15);  // pillar surface minus inflation

  // The same goal again is no change; a new goal id (pointing away from the pillar) is.
  sendGoal(7, Vector3d(20, 0, 1.5), 3500);
  EXPECT_EQ(sink_.got.size(), 2u);
  sendGoal(8, Vector3d(1, 4, 1.5), 4000);
  ASSERT_EQ(sink_.got.size(), 3u);
  EXPECT_TRUE(sink_.got[2].safe);
  EXPECT_EQ(sink_.got[2].goal_id, 8);
  EXPECT_EQ(sink_.got[2].map_seq, 2);
  // A moved goal with the same id is a change too.
  sendGoal(8, Vector3d(9, 0, 1.5), 4500);
  ASSERT_EQ(sink_.got.size(), 4u);
  EXPECT_FALSE(sink_.got[3].safe);
  // Odometry alone does not trigger an answer.
  sendPose(Vector3d(1.2, 0, 1.5), 5000);
  EXPECT_EQ(sink_.got.size(), 4u);
}

TEST_F(AwarenessNodeTest, NarrowGapIsReported) {
  sendPose(Vector3d(0.5, 0, 1.5), 1000);
  sendGoal(1, Vector3d(9, 0, 1.5), 1000);
  sendMap(mmh::makeKeyframe(window({Vector3d(3, 1, 0.3), Vector3d(3, -1, 0.3)}), 1), 2000);
  ASSERT_EQ(sink_.got.size(), 1u);
  EXPECT_FALSE(sink_.got[0].safe);
  EXPECT_EQ(sink_.got[0].reason, mmh::awareness_t::REASON_NARROW);
}

TEST_F(AwarenessNodeTest, MapGapStopsAnswersUntilTheNextKeyframe) {
  sendPose(Vector3d(1, 0, 1.5), 1000);
  sendGoal(1, Vector3d(9, 0, 1.5), 1000);
  const mmh::VoxelGrid g = window();
  sendMap(mmh::makeKeyframe(g, 1), 2000);
  ASSERT_EQ(sink_.got.size(), 1u);
  sendMap(mmh::makeDelta(g, 3, {}), 3000);  // map_seq 2 was lost
  EXPECT_EQ(sink_.got.size(), 1u);
  EXPECT_EQ(node_ctx_.counter("map_gap"), 1);
  sendMap(mmh::makeDelta(g, 4, {}), 4000);
  EXPECT_EQ(sink_.got.size(), 1u);
  EXPECT_EQ(node_ctx_.counter("map_waiting_for_keyframe"), 1);
  sendMap(mmh::makeKeyframe(g, 5), 5000);
  ASSERT_EQ(sink_.got.size(), 2u);
  EXPECT_EQ(sink_.got[1].map_seq, 5);
}

TEST_F(AwarenessNodeTest, BadMessagesAreRejectedWithoutAnswer) {
  sendPose(Vector3d(1, 0, 1.5), 1000);
  sendGoal(1, Vector3d(9, 0, 1.5), 1000);
  mmh::goal_t nan_goal{};
  nan_goal.header.utime = 1500;
  nan_goal.goal_id = 2;
  nan_goal.position[0] = NAN;
  test_ctx_.publish(mmh::channels::kGoal, nan_goal);
  mmh::local_map_t broken = mmh::makeKeyframe(window(), 1);
  broken.header.utime = 2000;
  broken.runs.assign(broken.runs.size(), 0xff);  // varints that never end
  test_ctx_.publish(mmh::channels::kLocalMap, broken);
  drain();
  EXPECT_TRUE(sink_.got.empty());
  EXPECT_GE(node_ctx_.messagesRejected(), 2);
}

TEST(AwarenessParams, BadValuesNameTheKey) {
  EXPECT_THROW(
      {
        try {
          mmh::awareness::loadParams(
              mmh::Config::fromString("map: {inflation_m: 0.3}\nawareness: {sensor_range_m: -1, "
                                      "narrow_probe_dist_m: 0.8}"));
        } catch (const mmh::ConfigError& e) {
          EXPECT_NE(std::string(e.what()).find("awareness.sensor_range_m"), std::string::npos);
          throw;
        }
      },
      mmh::ConfigError);
  EXPECT_THROW(mmh::awareness::loadParams(mmh::Config::fromString(
                   "map: {inflation_m: 0.3}\nawareness: {sensor_range_m: 4.5}")),
               mmh::ConfigError);
  const auto p = mmh::awareness::loadParams(
      mmh::Config::loadFile(MMH_SOURCE_DIR "/deploy/config/default.yaml"));
  EXPECT_DOUBLE_EQ(p.algorithm.sensor_range_m, 4.5);
}
