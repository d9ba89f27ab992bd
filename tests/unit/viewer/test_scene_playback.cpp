// mmh-viewer --log: the scene at any time of a recorded flight is the live scene after the
// messages up to that time, however the slider got there (forwards, backwards, across
// checkpoints), and playing on sends what the live viewer sent.
#include <gtest/gtest.h>

#include <algorithm>

#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/viewer/scene_playback.hpp"
#include "mmh/viewer/scene_topics.hpp"

namespace mmh::viewer {
namespace {
using nlohmann::json;

const char* const kTopics[] = {topics::kMapVoxels,  topics::kOdometry,  topics::kFlownPath,
                               topics::kTrajectory, topics::kAwareness, topics::kPlanRequest,
                               topics::kPlanResult, topics::kDecision,  topics::kHeartbeat,
                               topics::kMission,    topics::kPlanDebug};

int64_t us(double t_s) {
  return static_cast<int64_t>(t_s * 1e6 + 0.5);
}

// Every channel's snapshot, as what a client that connects now receives.
json snapshotOf(const SceneState& scene) {
  json out = json::object();
  for (const char* topic : kTopics) {
    json list = json::array();
    for (const SceneMessage& m : scene.snapshot(topic))
      list.push_back({{"utime", m.utime}, {"payload", m.payload}});
    out[topic] = std::move(list);
  }
  return out;
}

json sentOf(const SceneMessages& messages) {
  json out = json::array();
  for (const SceneMessage& m : messages)
    out.push_back({{"topic", m.topic}, {"utime", m.utime}, {"payload", m.payload}});
  return out;
}

// A 30 s flight along x: maps at 15 Hz (a keyframe each second, deltas between, obstacles
// appearing and going), odometry at 100 Hz, a commit, a decision, an answer and its debug every
// half second, heartbeats at 1 Hz. Answers are stamped a little before the message that came
// before them in the log, as the planners' clocks lag the arbiter's.
std::vector<RecordedMessage> recordedFlight() {
  std::vector<RecordedMessage> log;
  VoxelGrid grid(0.1, Eigen::Vector3i(-20, -20, 0), {40, 40, 20});
  int64_t map_seq = 0;
  for (int step = 0; step < 3000; ++step) {
    const double t = 1.0 + 0.01 * step;
    odometry_t odometry{};
    odometry.header.utime = us(t);
    odometry.position[0] = 0.02 * step;
    odometry.velocity[0] = 2.0;
    odometry.orientation[0] = 1.0;
    log.emplace_back(odometry);
    if (step % 7 == 0) {  // ~15 Hz
      const int k = step / 7;
      const Eigen::Vector3i cell(k % 40, (3 * k) % 40, k % 20);
      std::vector<CellChange> changes = {
          {grid.linearIndex(cell), k % 3 == 2 ? Occupancy::kFree : Occupancy::kOccupied}};
      grid.set(cell, changes[0].second);
      local_map_t map =
          k % 15 == 0 ? makeKeyframe(grid, ++map_seq) : makeDelta(grid, ++map_seq, changes);
      map.header.utime = us(t);
      log.emplace_back(map);
    }
    if (step % 50 == 25) {
      const int64_t id = step;
      plan_request_t request{};
      request.header.utime = us(t);
      request.request_id = id;
      request.mode = static_cast<int8_t>(plan_request_t::MODE_FPM + (step / 50) % 3);
      log.emplace_back(request);
      plan_result_t result{};
      result.header.utime = us(t - 0.003);  // earlier than the request before it
      result.request_id = id;
      result.mode = request.mode;
      log.emplace_back(result);
      PlanDebug debug;
      debug.paths = {{Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0.02 * step, 0, 1)}};
      Eigen::Matrix<double, Eigen::Dynamic, 4> box(6, 4);
      box << 1, 0, 0, 1, -1, 0, 0, 1, 0, 1, 0, 1, 0, -1, 0, 1, 0, 0, 1, 2, 0, 0, -1, 0;
      debug.polytopes = {box};
      plan_debug_t debug_msg = toDebugMsg(debug, id, plan_request_t::MODE_SOM, true);
      debug_msg.header.utime = us(t - 0.002);
      log.emplace_back(debug_msg);
      Piece piece;
      piece.duration = 1.0;
      piece.coeffs(0, 0) = 0.02 * step;
      piece.coeffs(0, 1) = 2.0;
      trajectory_t trajectory{};
      toMsg(Trajectory({piece}), trajectory);
      trajectory.header.utime = us(t + 0.001);
      trajectory.trajectory_id = id;
      trajectory.source_mode = request.mode;
      log.emplace_back(trajectory);
      arbiter_status_t status{};
      status.header.utime = us(t + 0.001);
      status.decision_seq = step / 50 + 1;
      status.outcome = arbiter_status_t::OUTCOME_COMMITTED;
      status.committed_mode = request.mode;
      log.emplace_back(status);
      awareness_t awareness{};
      awareness.header.utime = us(t);
      awareness.reason = static_cast<int8_t>((step / 50) % 3);
      log.emplace_back(awareness);
    }
    if (step % 100 == 0) {
      for (const char* service : {"mmh-som", "mmh-arbiter"}) {
        heartbeat_t hb{};
        hb.header.utime = us(t);
        hb.service = service;
        hb.host = "vehicle";
        hb.uptime_s = step / 100;
        log.emplace_back(hb);
      }
      mission_status_t mission{};
      mission.header.utime = us(t);
      mission.active = true;
      mission.distance_m = 0.02 * step;
      log.emplace_back(mission);
    }
  }
  return log;
}

// The live scene after the log's prefix that a viewer had received by time t.
json liveAt(const std::vector<RecordedMessage>& log, int64_t utime) {
  SceneState live;
  int64_t clock = 0;
  for (const RecordedMessage& m : log) {
    clock = std::max(clock, utimeOf(m));
    if (clock > utime) break;
    feed(live, m);
  }
  return snapshotOf(live);
}

TEST(ScenePlayback, TheSceneAtAnyTimeIsTheLiveSceneAfterTheMessagesUpToIt) {
  const std::vector<RecordedMessage> log = recordedFlight();
  ScenePlayback playback(log);
  EXPECT_EQ(playback.numMessages(), log.size());
  EXPECT_EQ(playback.startUtime(), us(1.0));
  EXPECT_GE(playback.endUtime(), us(30.99));
  // Forwards, backwards across checkpoints, to the ends, inside one message's microsecond.
  for (double t : {5.0, 12.3, 2.0, 29.5, 29.5, 1.0, 17.2555, 0.0, 100.0, 8.0}) {
    const int64_t utime = us(t);
    playback.seek(utime);
    const int64_t clamped = std::clamp(utime, playback.startUtime(), playback.endUtime());
    EXPECT_EQ(playback.nowUtime(), clamped);
    EXPECT_EQ(snapshotOf(playback.scene()), liveAt(log, clamped)) << "at t = " << t;
  }
}

TEST(ScenePlayback, AJumpShowsTheMapTheTrajectoryAndTheDecisionsOfThatTime) {
  ScenePlayback playback(recordedFlight());
  playback.seek(us(20.0));
  const size_t voxels_late = playback.scene().voxels().numOccupied();
  const size_t decisions_late = playback.scene().snapshot(topics::kDecision).size();
  playback.seek(us(3.0));
  EXPECT_LT(playback.scene().voxels().numOccupied(), voxels_late);
  const SceneMessages decisions = playback.scene().snapshot(topics::kDecision);
  EXPECT_LT(decisions.size(), decisions_late);
  ASSERT_FALSE(decisions.empty());
  for (const SceneMessage& d : decisions) EXPECT_LE(d.utime, us(3.0));
  const SceneMessages trajectories = playback.scene().snapshot(topics::kTrajectory);
  ASSERT_FALSE(trajectories.empty());
  EXPECT_EQ(trajectories.back().payload["id"], 175);  // the commit at 2.75 s
  const SceneMessages path = playback.scene().snapshot(topics::kFlownPath);
  ASSERT_EQ(path.size(), 1u);
  EXPECT_LE(path[0].payload["t"].back().get<double>(), 3.0);
}

TEST(ScenePlayback, PlayingOnSendsWhatTheLiveViewerSent) {
  const std::vector<RecordedMessage> log = recordedFlight();
  ScenePlayback playback(log);
  playback.seek(us(4.0));
  SceneState live;
  json expected = json::array(), played = json::array();
  int64_t clock = 0;
  for (const RecordedMessage& m : log) {
    clock = std::max(clock, utimeOf(m));
    if (clock > us(9.0)) break;
    const SceneMessages sent = feed(live, m);
    if (clock <= us(4.0)) continue;  // in the scene before playing on
    for (const json& j : sentOf(sent)) expected.push_back(j);
  }
  for (double t = 4.1; t <= 9.0 + 1e-9; t += 0.1)
    for (const json& j : sentOf(playback.advance(us(t)))) played.push_back(j);
  EXPECT_FALSE(expected.empty());
  EXPECT_EQ(played, expected);
  // It does not go back.
  EXPECT_TRUE(playback.advance(us(2.0)).empty());
  EXPECT_EQ(playback.nowUtime(), us(9.0));
}

TEST(ScenePlayback, MessagesStampedZeroBelongToTheStartOfTheFlight) {
  std::vector<RecordedMessage> log;
  heartbeat_t hb{};  // a service's first heartbeat, before its clock saw a message
  hb.service = "mmh-sim";
  log.emplace_back(hb);
  for (const RecordedMessage& m : recordedFlight()) log.push_back(m);
  ScenePlayback playback(log);
  EXPECT_EQ(playback.startUtime(), us(1.0));
  playback.seek(0);
  EXPECT_EQ(playback.nowUtime(), us(1.0));
  EXPECT_EQ(snapshotOf(playback.scene()), liveAt(log, us(1.0)));
  EXPECT_EQ(playback.scene().snapshot(topics::kHeartbeat).size(), 3u);  // and the two at 1 s
}

TEST(ScenePlayback, AnEmptyLogIsAnEmptyScene) {
  ScenePlayback playback({});
  playback.seek(us(5.0));
  EXPECT_EQ(playback.nowUtime(), 0);
  EXPECT_TRUE(playback.scene().snapshot(topics::kOdometry).empty());
}

}  // namespace
}  // namespace mmh::viewer
