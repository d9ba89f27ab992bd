// What the ground station knows about one vehicle, built from its LCM messages, and the messages
// that keep a client's copy current: each on*() call returns the deltas to send now (changed
// voxels, a new path sample, a committed trajectory, ...); snapshot(topic) is what a client that
// subscribes late needs first. No LCM and no network here.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mmh/arbiter_status_t.hpp"
#include "mmh/awareness_t.hpp"
#include "mmh/heartbeat_t.hpp"
#include "mmh/local_map_t.hpp"
#include "mmh/mission_status_t.hpp"
#include "mmh/odometry_t.hpp"
#include "mmh/plan_debug_t.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/plan_result_t.hpp"
#include "mmh/trajectory_t.hpp"
#include "mmh/viewer/flown_path.hpp"
#include "mmh/viewer/voxel_layer.hpp"

namespace mmh::viewer {

struct SceneMessage {
  std::string topic;  // scene_topics.hpp
  int64_t utime = 0;  // message clock of the LCM message it came from
  nlohmann::json payload;
};
using SceneMessages = std::vector<SceneMessage>;

struct SceneOptions {
  double odometry_period_s = 0.05;  // forward ODOMETRY at most this often (100 Hz in, 20 Hz out)
  double path_spacing_m = 0.05;     // a flown-path sample per this distance ...
  double path_interval_s = 0.5;     // ... or this time
  double trajectory_sample_s = 0.05;
  size_t max_path_samples = 20000;
  size_t max_trajectories = 300;  // committed trajectories kept for late clients
  size_t max_decisions = 5000;
  size_t max_plan_results = 5000;
};

class SceneState {
 public:
  explicit SceneState(SceneOptions options = {});

  SceneMessages onLocalMap(const local_map_t& msg);
  SceneMessages onOdometry(const odometry_t& msg);
  SceneMessages onTrajectory(const trajectory_t& msg);
  SceneMessages onAwareness(const awareness_t& msg);
  SceneMessages onPlanRequest(const plan_request_t& msg);
  SceneMessages onPlanResult(const plan_result_t& msg);
  SceneMessages onArbiterStatus(const arbiter_status_t& msg);
  SceneMessages onHeartbeat(const heartbeat_t& msg);
  SceneMessages onMissionStatus(const mission_status_t& msg);
  SceneMessages onPlanDebug(const plan_debug_t& msg);
  // The on*() of the message's type, for callers generic in the type.
  SceneMessages apply(const local_map_t& msg) { return onLocalMap(msg); }
  SceneMessages apply(const odometry_t& msg) { return onOdometry(msg); }
  SceneMessages apply(const trajectory_t& msg) { return onTrajectory(msg); }
  SceneMessages apply(const awareness_t& msg) { return onAwareness(msg); }
  SceneMessages apply(const plan_request_t& msg) { return onPlanRequest(msg); }
  SceneMessages apply(const plan_result_t& msg) { return onPlanResult(msg); }
  SceneMessages apply(const arbiter_status_t& msg) { return onArbiterStatus(msg); }
  SceneMessages apply(const heartbeat_t& msg) { return onHeartbeat(msg); }
  SceneMessages apply(const mission_status_t& msg) { return onMissionStatus(msg); }
  SceneMessages apply(const plan_debug_t& msg) { return onPlanDebug(msg); }

  // Everything a client subscribing to `topic` now needs, oldest first (empty if nothing yet).
  SceneMessages snapshot(const std::string& topic) const;

  const VoxelLayer& voxels() const { return voxels_; }
  const FlownPath& path() const { return path_; }
  int64_t mapsRefused() const { return maps_refused_; }

 private:
  static void keep(std::deque<SceneMessage>& history, SceneMessage message, size_t limit);

  SceneOptions options_;
  VoxelLayer voxels_;
  FlownPath path_;
  int64_t maps_refused_ = 0;
  int64_t last_map_utime_ = 0;
  int64_t last_odometry_forwarded_ = 0;
  SceneMessages latest_odometry_, latest_awareness_, latest_mission_;
  std::map<int, SceneMessage> latest_request_by_mode_, latest_debug_by_mode_;
  std::map<std::string, SceneMessage> latest_heartbeat_by_process_;
  std::deque<SceneMessage> trajectories_, decisions_, plan_results_;
};

}  // namespace mmh::viewer
