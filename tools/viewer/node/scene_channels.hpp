// The LCM channels the viewer's scene is made of, with their message types: one list for the
// live subscriptions (viewer_node) and the reader of recorded flights (log_viewer).
#pragma once

#include "mmh/common/lcm_runtime.hpp"
#include "mmh/viewer/scene_state.hpp"

namespace mmh::viewer {

template <class T>
struct MessageType {
  using type = T;
};

// Calls f(base_channel, MessageType<Msg>{}) for each channel.
template <class F>
void forEachSceneChannel(F&& f) {
  namespace ch = channels;
  f(ch::kLocalMap, MessageType<local_map_t>{});
  f(ch::kOdometry, MessageType<odometry_t>{});
  f(ch::kTrajectory, MessageType<trajectory_t>{});
  f(ch::kAwareness, MessageType<awareness_t>{});
  for (const char* request : {ch::kPlanRequestFpm, ch::kPlanRequestSom, ch::kPlanRequestEam})
    f(request, MessageType<plan_request_t>{});
  f(ch::kPlanResult, MessageType<plan_result_t>{});
  f(ch::kArbiterStatus, MessageType<arbiter_status_t>{});
  f(ch::kHeartbeat, MessageType<heartbeat_t>{});
  f(ch::kMissionStatus, MessageType<mission_status_t>{});
  f(ch::kPlanDebug, MessageType<plan_debug_t>{});
}

}  // namespace mmh::viewer
