#include "mmh/viewer/scene_state.hpp"

#include "mmh/viewer/scene_json.hpp"
#include "mmh/viewer/scene_topics.hpp"

namespace mmh::viewer {

SceneState::SceneState(SceneOptions options)
    : options_(options),
      path_(options.path_spacing_m, options.path_interval_s, options.max_path_samples) {}

void SceneState::keep(std::deque<SceneMessage>& history, SceneMessage message, size_t limit) {
  history.push_back(std::move(message));
  while (history.size() > limit) history.pop_front();
}

SceneMessages SceneState::onLocalMap(const local_map_t& msg) {
  VoxelChanges changes;
  if (!voxels_.apply(msg, &changes)) {
    ++maps_refused_;
    return {};
  }
  last_map_utime_ = msg.header.utime;
  if (changes.empty()) return {};
  return {{topics::kMapVoxels, msg.header.utime, voxelsJson(changes, voxels_.resolution(), false)}};
}

SceneMessages SceneState::onOdometry(const odometry_t& msg) {
  SceneMessages out;
  if (auto sample = path_.add(msg))
    out.push_back({topics::kFlownPath, msg.header.utime, pathJson({*sample}, false)});
  const int64_t period_us = static_cast<int64_t>(options_.odometry_period_s * 1e6);
  if (latest_odometry_.empty() || msg.header.utime - last_odometry_forwarded_ >= period_us ||
      msg.header.utime < last_odometry_forwarded_) {
    last_odometry_forwarded_ = msg.header.utime;
    latest_odometry_ = {{topics::kOdometry, msg.header.utime, odometryJson(msg)}};
    out.push_back(latest_odometry_.front());
  }
  return out;
}

SceneMessages SceneState::onTrajectory(const trajectory_t& msg) {
  // The arbiter republishes the committed trajectory; only a new id is a new commit.
  if (!trajectories_.empty() && trajectories_.back().payload["id"] == msg.trajectory_id) return {};
  SceneMessage m{topics::kTrajectory, msg.header.utime,
                 trajectoryJson(msg, options_.trajectory_sample_s)};
  keep(trajectories_, m, options_.max_trajectories);
  return {m};
}

SceneMessages SceneState::onAwareness(const awareness_t& msg) {
  latest_awareness_ = {{topics::kAwareness, msg.header.utime, awarenessJson(msg)}};
  return latest_awareness_;
}

SceneMessages SceneState::onPlanRequest(const plan_request_t& msg) {
  SceneMessage m{topics::kPlanRequest, msg.header.utime, planRequestJson(msg)};
  latest_request_by_mode_[msg.mode] = m;
  return {m};
}

SceneMessages SceneState::onPlanResult(const plan_result_t& msg) {
  SceneMessage m{topics::kPlanResult, msg.header.utime, planResultJson(msg)};
  keep(plan_results_, m, options_.max_plan_results);
  return {m};
}

SceneMessages SceneState::onArbiterStatus(const arbiter_status_t& msg) {
  SceneMessage m{topics::kDecision, msg.header.utime, decisionJson(msg)};
  keep(decisions_, m, options_.max_decisions);
  return {m};
}

SceneMessages SceneState::onHeartbeat(const heartbeat_t& msg) {
  SceneMessage m{topics::kHeartbeat, msg.header.utime, heartbeatJson(msg)};
  latest_heartbeat_by_process_[msg.service + "@" + msg.host + ":" + std::to_string(msg.pid)] = m;
  return {m};
}

SceneMessages SceneState::onMissionStatus(const mission_status_t& msg) {
  latest_mission_ = {{topics::kMission, msg.header.utime, missionJson(msg)}};
  return latest_mission_;
}

SceneMessages SceneState::onPlanDebug(const plan_debug_t& msg) {
  SceneMessage m{topics::kPlanDebug, msg.header.utime, planDebugJson(msg)};
  latest_debug_by_mode_[msg.mode] = m;
  return {m};
}

SceneMessages SceneState::snapshot(const std::string& topic) const {
  const auto fromHistory = [](const std::deque<SceneMessage>& h) {
    return SceneMessages(h.begin(), h.end());
  };
  const auto latestOf = [](const auto& latest_by_key) {
    SceneMessages out;
    for (const auto& entry : latest_by_key) out.push_back(entry.second);
    return out;
  };
  if (topic == topics::kMapVoxels) {
    if (voxels_.numOccupied() == 0) return {};
    VoxelChanges all;
    all.added = voxels_.allOccupied();
    return {{topic, last_map_utime_, voxelsJson(all, voxels_.resolution(), true)}};
  }
  if (topic == topics::kFlownPath) {
    if (path_.samples().empty()) return {};
    const std::vector<PathSample> samples(path_.samples().begin(), path_.samples().end());
    const int64_t utime = static_cast<int64_t>(samples.back().t_s * 1e6);
    return {{topic, utime, pathJson(samples, true)}};
  }
  if (topic == topics::kOdometry) return latest_odometry_;
  if (topic == topics::kTrajectory) return fromHistory(trajectories_);
  if (topic == topics::kAwareness) return latest_awareness_;
  if (topic == topics::kPlanRequest) return latestOf(latest_request_by_mode_);
  if (topic == topics::kPlanResult) return fromHistory(plan_results_);
  if (topic == topics::kPlanDebug) return latestOf(latest_debug_by_mode_);
  if (topic == topics::kDecision) return fromHistory(decisions_);
  if (topic == topics::kHeartbeat) return latestOf(latest_heartbeat_by_process_);
  if (topic == topics::kMission) return latest_mission_;
  return {};
}

}  // namespace mmh::viewer
