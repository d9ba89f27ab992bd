#include <gtest/gtest.h>

#include "mmh/common/msg_convert.hpp"
#include "mmh/viewer/channel_schemas.hpp"
#include "mmh/viewer/scene_json.hpp"
#include "mmh/viewer/scene_state.hpp"
#include "mmh/viewer/scene_topics.hpp"

namespace mmh::viewer {
namespace {
using nlohmann::json;

TEST(SceneJson, NumbersAreRoundedSoMessagesStaySmall) {
  const double p[3] = {1.23456789, -0.0004, 2.0};
  EXPECT_EQ(vec3Json(p).dump(), "[1.235,-0.0,2.0]");
  odometry_t m{};
  m.header.utime = 1'234'567'891;
  m.velocity[0] = 3.0;
  m.velocity[1] = 4.0;
  m.orientation[0] = 1.0;
  const json j = odometryJson(m);
  EXPECT_DOUBLE_EQ(j["t"].get<double>(), 1234.567891);
  EXPECT_DOUBLE_EQ(j["speed"].get<double>(), 5.0);
}

TEST(SceneJson, TrajectoryIsSampledFromStartToEnd) {
  Piece piece;
  piece.duration = 2.0;
  piece.coeffs(0, 1) = 1.5;  // x = 1.5 t
  trajectory_t m{};
  toMsg(Trajectory({piece}), m);
  m.trajectory_id = 7;
  m.source_mode = plan_request_t::MODE_SOM;
  const json j = trajectoryJson(m, 0.5);
  EXPECT_EQ(j["mode_name"], "SOM");
  EXPECT_EQ(j["points"].size(), 15u);  // 5 samples over 2 s
  EXPECT_DOUBLE_EQ(j["points"][12].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(j["max_speed"].get<double>(), 1.5);
  trajectory_t empty{};
  EXPECT_TRUE(trajectoryJson(empty, 0.5)["points"].empty());
}

TEST(SceneJson, DecisionNamesTriggersOutcomesAndModes) {
  arbiter_status_t m{};
  m.trigger = arbiter_status_t::TRIGGER_COLLISION;
  m.outcome = arbiter_status_t::OUTCOME_COMMITTED;
  m.awareness_reason = awareness_t::REASON_NARROW;
  m.modes_asked = (1 << plan_request_t::MODE_SOM) | (1 << plan_request_t::MODE_EAM);
  m.modes_answered_ok = 1 << plan_request_t::MODE_EAM;
  m.committed_mode = plan_request_t::MODE_EAM;
  m.compute_us_eam = 1500;
  m.detail = "committed EAM";
  m.header.utime = 5'012'500;
  m.threat_seen_utime = 5'000'000;  // the danger it answers was seen 12.5 ms before
  const json j = decisionJson(m);
  EXPECT_EQ(j["trigger"], "collision");
  EXPECT_EQ(j["outcome"], "committed");
  EXPECT_EQ(j["awareness_reason"], "narrow");
  EXPECT_EQ(j["modes_asked"], "SOM+EAM");
  EXPECT_EQ(j["committed_mode"], "EAM");
  EXPECT_DOUBLE_EQ(j["compute_ms"]["EAM"].get<double>(), 1.5);
  EXPECT_EQ(j["detail"], "committed EAM");
  EXPECT_DOUBLE_EQ(j["reaction_ms"].get<double>(), 12.5);
  m.threat_seen_utime = 0;
  EXPECT_DOUBLE_EQ(decisionJson(m)["reaction_ms"].get<double>(), -1.0);
}

TEST(SceneJson, HeartbeatCountersBecomeAnObject) {
  heartbeat_t m{};
  m.service = "mmh-mapping";
  m.state = heartbeat_t::STATE_DEGRADED;
  m.num_counters = 2;
  m.counter_names = {"rejected_invalid", "map_gap"};
  m.counter_values = {3, 1};
  const json j = heartbeatJson(m);
  EXPECT_EQ(j["state"], "DEGRADED");
  EXPECT_EQ(j["counters"]["rejected_invalid"], 3);
  EXPECT_EQ(j["counters"]["map_gap"], 1);
}

TEST(SceneJson, AwarenessWithoutABlockedPointSaysNull) {
  awareness_t m{};
  m.reason = awareness_t::REASON_BLOCKED;
  EXPECT_TRUE(awarenessJson(m)["first_blocked"].is_null());
  m.has_blocked_point = true;
  m.first_blocked[2] = 1.2;
  EXPECT_EQ(awarenessJson(m)["first_blocked"].dump(), "[0.0,0.0,1.2]");
  EXPECT_EQ(awarenessJson(m)["reason_name"], "blocked");
}

// Every message the scene state writes has each property its channel's schema requires.
TEST(SceneJson, MessagesMatchTheAdvertisedSchemas) {
  SceneState scene;
  odometry_t odometry{};
  odometry.orientation[0] = 1.0;
  scene.onOdometry(odometry);
  VoxelGrid grid(0.1, Eigen::Vector3i::Zero(), {4, 4, 4});
  grid.set({1, 1, 1}, Occupancy::kOccupied);
  scene.onLocalMap(makeKeyframe(grid, 1));
  trajectory_t trajectory{};
  trajectory.trajectory_id = 1;
  scene.onTrajectory(trajectory);
  scene.onAwareness(awareness_t{});
  scene.onPlanRequest(plan_request_t{});
  scene.onPlanResult(plan_result_t{});
  scene.onArbiterStatus(arbiter_status_t{});
  scene.onHeartbeat(heartbeat_t{});
  scene.onMissionStatus(mission_status_t{});
  plan_debug_t debug{};
  debug.mode = plan_request_t::MODE_SOM;
  scene.onPlanDebug(debug);
  EXPECT_EQ(viewerChannels().size(), 11u);  // live: no playback channel
  const std::vector<ChannelInfo> channels = viewerChannels(true);
  ASSERT_EQ(channels.size(), 12u);
  for (const ChannelInfo& channel : channels) {
    SCOPED_TRACE(channel.topic);
    EXPECT_EQ(channel.id, static_cast<uint32_t>(&channel - &channels[0] + 1));
    const SceneMessages messages =
        channel.topic == topics::kPlayback
            ? SceneMessages{{channel.topic, 0, playbackJson(PlaybackState{})}}
            : scene.snapshot(channel.topic);
    ASSERT_FALSE(messages.empty());
    for (const json& key : channel.schema["required"])
      EXPECT_TRUE(messages.front().payload.contains(key.get<std::string>())) << key;
    // LCM's booleans are int8_t: the JSON must still say true / false where the schema does.
    for (const auto& [name, property] : channel.schema["properties"].items()) {
      if (property.value("type", json()) == "boolean") {
        EXPECT_TRUE(messages.front().payload[name].is_boolean()) << channel.topic << " " << name;
      }
    }
    EXPECT_EQ(messages.front().payload.size(), channel.schema["properties"].size());
  }
}

}  // namespace
}  // namespace mmh::viewer
