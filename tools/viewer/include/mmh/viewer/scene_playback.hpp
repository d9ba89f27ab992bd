// A recorded flight for `mmh-viewer --log`: its messages in log order and the scene at any time
// of it. The scene at time t is the live scene after the log's messages up to t: the longest
// prefix of the log whose message clock (header.utime, as a running maximum, so that the prefix
// is what a live viewer had received) stays within t. Scrubbing thus shows what the live page
// showed at that moment. No LCM transport and no file reading here (the node reads the log).
#pragma once

#include <cstdint>
#include <variant>
#include <vector>

#include "mmh/viewer/scene_state.hpp"

namespace mmh::viewer {

using RecordedMessage =
    std::variant<local_map_t, odometry_t, trajectory_t, awareness_t, plan_request_t, plan_result_t,
                 arbiter_status_t, heartbeat_t, mission_status_t, plan_debug_t>;

// Applies one message to the scene (the on*() of its type) and returns the scene messages.
SceneMessages feed(SceneState& scene, const RecordedMessage& message);
int64_t utimeOf(const RecordedMessage& message);

class ScenePlayback {
 public:
  // Starts at the first message's time, with nothing applied yet beyond it. Messages stamped 0
  // (a service's first HEARTBEAT, before its clock has seen a message) belong to the start and
  // do not make it.
  explicit ScenePlayback(std::vector<RecordedMessage> messages, SceneOptions options = {});

  int64_t startUtime() const { return start_utime_; }
  int64_t endUtime() const { return clock_.empty() ? 0 : clock_.back(); }
  int64_t nowUtime() const { return now_; }
  size_t numMessages() const { return messages_.size(); }
  size_t applied() const { return next_; }  // messages in the scene

  // Jumps to time t (clamped to the log): on from here when t is later, again from the start
  // (from the latest checkpoint before t) when earlier. The scene messages on the way are not
  // returned: clients need the snapshots of the new scene.
  void seek(int64_t utime);
  // Plays on to time t (not before now): the scene messages of what it applied, as live.
  SceneMessages advance(int64_t utime);
  const SceneState& scene() const { return scene_; }

 private:
  void applyUpTo(int64_t utime, SceneMessages* out);

  std::vector<RecordedMessage> messages_;
  std::vector<int64_t> clock_;  // running maximum of header.utime over messages_
  int64_t start_utime_ = 0;     // the first non-zero clock
  SceneOptions options_;
  SceneState scene_;
  size_t next_ = 0;  // first message not in the scene
  int64_t now_ = 0;
  // Scenes every checkpoint_spacing_us_ of the log, so that a jump back replays little.
  struct Checkpoint {
    size_t next;
    SceneState scene;
  };
  int64_t checkpointClock(const Checkpoint& c) const;  // of its last message
  std::vector<Checkpoint> checkpoints_;
  int64_t checkpoint_spacing_us_ = 1;
};

}  // namespace mmh::viewer
