#include <gtest/gtest.h>

#include "mmh/common/msg_convert.hpp"
#include "mmh/viewer/scene_state.hpp"
#include "mmh/viewer/scene_topics.hpp"

namespace mmh::viewer {
namespace {

odometry_t odometryAt(double t_s, double x) {
  odometry_t m{};
  m.header.utime = static_cast<int64_t>(t_s * 1e6);
  m.position[0] = x;
  m.velocity[0] = 2.0;
  m.orientation[0] = 1.0;
  return m;
}

trajectory_t trajectoryWithId(int64_t id, int8_t mode) {
  Piece piece;
  piece.duration = 1.0;
  piece.coeffs(0, 1) = 1.0;  // x = t
  trajectory_t m{};
  toMsg(Trajectory({piece}), m);
  m.trajectory_id = id;
  m.source_mode = mode;
  m.header.utime = 1'000'000 * id;
  return m;
}

TEST(SceneState, OdometryIsDecimatedAndTheFlownPathSampledByDistance) {
  SceneState scene;
  int odometry = 0, path = 0;
  for (int i = 0; i < 100; ++i) {  // 1 s at 100 Hz, 2 m/s
    for (const SceneMessage& m : scene.onOdometry(odometryAt(1.0 + 0.01 * i, 0.02 * i))) {
      odometry += m.topic == topics::kOdometry;
      path += m.topic == topics::kFlownPath;
    }
  }
  EXPECT_EQ(odometry, 20);  // 20 Hz
  EXPECT_EQ(path, 34);      // 2 cm steps: a sample every third, once 5 cm are flown
  const SceneMessages snapshot = scene.snapshot(topics::kFlownPath);
  ASSERT_EQ(snapshot.size(), 1u);
  EXPECT_TRUE(snapshot[0].payload["snapshot"].get<bool>());
  EXPECT_EQ(snapshot[0].payload["speed"].size(), static_cast<size_t>(path));
  EXPECT_EQ(scene.snapshot(topics::kOdometry).size(), 1u);
}

TEST(SceneState, ATrajectoryIsSentOnceWhenCommittedAndKeptForLateClients) {
  SceneState scene;
  EXPECT_EQ(scene.onTrajectory(trajectoryWithId(1, plan_request_t::MODE_FPM)).size(), 1u);
  EXPECT_TRUE(scene.onTrajectory(trajectoryWithId(1, plan_request_t::MODE_FPM)).empty());
  const SceneMessages sent = scene.onTrajectory(trajectoryWithId(2, plan_request_t::MODE_EAM));
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].payload["mode_name"], "EAM");
  const SceneMessages snapshot = scene.snapshot(topics::kTrajectory);
  ASSERT_EQ(snapshot.size(), 2u);
  EXPECT_EQ(snapshot[0].payload["id"], 1);
  EXPECT_EQ(snapshot[1].payload["id"], 2);
}

TEST(SceneState, ALateClientGetsTheWholeMapOnceThenDeltas) {
  SceneState scene;
  VoxelGrid grid(0.1, Eigen::Vector3i::Zero(), {10, 10, 10});
  grid.set({1, 1, 1}, Occupancy::kOccupied);
  grid.set({2, 2, 2}, Occupancy::kOccupied);
  local_map_t keyframe = makeKeyframe(grid, 1);
  keyframe.header.utime = 5'000'000;
  ASSERT_EQ(scene.onLocalMap(keyframe).size(), 1u);
  // The same map again changes nothing: nothing to send.
  keyframe.map_seq = 2;
  EXPECT_TRUE(scene.onLocalMap(keyframe).empty());
  const SceneMessages snapshot = scene.snapshot(topics::kMapVoxels);
  ASSERT_EQ(snapshot.size(), 1u);
  EXPECT_TRUE(snapshot[0].payload["snapshot"].get<bool>());
  EXPECT_EQ(snapshot[0].payload["added"].size(), 6u);
  EXPECT_EQ(snapshot[0].utime, 5'000'000);
  EXPECT_TRUE(SceneState().snapshot(topics::kMapVoxels).empty());
}

TEST(SceneState, DecisionsHeartbeatsAndRequestsForLateClients) {
  SceneState scene;
  for (int i = 1; i <= 3; ++i) {
    arbiter_status_t status{};
    status.header.utime = i * 1'000'000;
    status.decision_seq = i;
    status.outcome = arbiter_status_t::OUTCOME_COMMITTED;
    scene.onArbiterStatus(status);
  }
  for (const char* service : {"mmh-som", "mmh-eam", "mmh-som"}) {
    heartbeat_t hb{};
    hb.service = service;
    hb.host = "vehicle";
    hb.pid = 42;
    scene.onHeartbeat(hb);
  }
  for (int8_t mode :
       {plan_request_t::MODE_SOM, plan_request_t::MODE_EAM, plan_request_t::MODE_SOM}) {
    plan_request_t request{};
    request.mode = mode;
    scene.onPlanRequest(request);
  }
  EXPECT_EQ(scene.snapshot(topics::kDecision).size(), 3u);
  EXPECT_EQ(scene.snapshot(topics::kHeartbeat).size(), 2u);    // one per process
  EXPECT_EQ(scene.snapshot(topics::kPlanRequest).size(), 2u);  // the latest per mode
  EXPECT_TRUE(scene.snapshot(topics::kMission).empty());
  EXPECT_TRUE(scene.snapshot("/no/such/topic").empty());
}

TEST(SceneState, HistoriesAreBounded) {
  SceneOptions options;
  options.max_decisions = 5;
  SceneState scene(options);
  for (int i = 1; i <= 20; ++i) {
    arbiter_status_t status{};
    status.decision_seq = i;
    scene.onArbiterStatus(status);
  }
  const SceneMessages decisions = scene.snapshot(topics::kDecision);
  ASSERT_EQ(decisions.size(), 5u);
  EXPECT_EQ(decisions.front().payload["seq"], 16);
}

}  // namespace
}  // namespace mmh::viewer
