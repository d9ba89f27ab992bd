#include "mmh/viewer/scene_playback.hpp"

#include <algorithm>

namespace mmh::viewer {
namespace {
// A scene copy (the map window is about 12 MB) every 2 s of the log, or at most kMaxCheckpoints
// of them over a long log: a jump back replays at most that much (a keyframe a second costs a
// pass over the window each), and the copies stay within a few hundred MB.
constexpr int64_t kMinCheckpointSpacingUs = 2'000'000;
constexpr int64_t kMaxCheckpoints = 24;
}  // namespace

SceneMessages feed(SceneState& scene, const RecordedMessage& message) {
  return std::visit([&scene](const auto& msg) { return scene.apply(msg); }, message);
}

int64_t utimeOf(const RecordedMessage& message) {
  return std::visit([](const auto& msg) { return msg.header.utime; }, message);
}

ScenePlayback::ScenePlayback(std::vector<RecordedMessage> messages, SceneOptions options)
    : messages_(std::move(messages)), options_(options), scene_(options) {
  clock_.reserve(messages_.size());
  int64_t latest = 0;
  for (const RecordedMessage& m : messages_) {
    latest = std::max(latest, utimeOf(m));
    clock_.push_back(latest);
    if (start_utime_ == 0) start_utime_ = latest;
  }
  checkpoint_spacing_us_ =
      std::max(kMinCheckpointSpacingUs, (endUtime() - startUtime()) / kMaxCheckpoints + 1);
  now_ = startUtime();
  checkpoints_.push_back({0, scene_});
  applyUpTo(now_, nullptr);
}

int64_t ScenePlayback::checkpointClock(const Checkpoint& c) const {
  return c.next > 0 ? clock_[c.next - 1] : startUtime();
}

void ScenePlayback::applyUpTo(int64_t utime, SceneMessages* out) {
  while (next_ < messages_.size() && clock_[next_] <= utime) {
    SceneMessages sent = feed(scene_, messages_[next_]);
    if (out) out->insert(out->end(), sent.begin(), sent.end());
    ++next_;
    const Checkpoint& last = checkpoints_.back();
    if (last.next < next_ && clock_[next_ - 1] - checkpointClock(last) >= checkpoint_spacing_us_)
      checkpoints_.push_back({next_, scene_});
  }
}

void ScenePlayback::seek(int64_t utime) {
  utime = std::clamp(utime, startUtime(), endUtime());
  // The last checkpoint that does not go beyond t (its messages are all within t): from there
  // when t is earlier than now, or when it is further on than what the scene has applied.
  auto it = std::upper_bound(
      checkpoints_.begin(), checkpoints_.end(), utime,
      [this](int64_t t, const Checkpoint& c) { return c.next > 0 && checkpointClock(c) > t; });
  const Checkpoint& from = *std::prev(it);
  if (utime < now_ || from.next > next_) {
    scene_ = from.scene;
    next_ = from.next;
  }
  now_ = utime;
  applyUpTo(now_, nullptr);
}

SceneMessages ScenePlayback::advance(int64_t utime) {
  SceneMessages out;
  now_ = std::clamp(std::max(utime, now_), startUtime(), endUtime());
  applyUpTo(now_, &out);
  return out;
}

}  // namespace mmh::viewer
