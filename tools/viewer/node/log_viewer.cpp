#include "log_viewer.hpp"

#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <stdexcept>

#include "mmh/common/checked_decode.hpp"
#include "mmh/viewer/scene_topics.hpp"
#include "scene_channels.hpp"

namespace mmh::viewer {
namespace {
// While playing, /mmh/playback goes out at most this often (the slider's position).
constexpr int64_t kStateEveryUs = 200'000;
constexpr double kMinSpeed = 0.05, kMaxSpeed = 50.0;

using Decoder = std::function<bool(const lcm::LogEvent&, std::vector<RecordedMessage>&)>;
}  // namespace

std::vector<RecordedMessage> readFlightLog(const std::string& path, const std::string& prefix,
                                           LogReadStats* stats) {
  std::map<std::string, Decoder> decoders;
  forEachSceneChannel([&](const char* channel, auto type) {
    using Msg = typename decltype(type)::type;
    decoders[prefix + channel] = [](const lcm::LogEvent& e, std::vector<RecordedMessage>& out) {
      Msg msg;
      if (e.datalen < 0 || decodeChecked(e.data, static_cast<uint32_t>(e.datalen), msg, nullptr) !=
                               DecodeOutcome::kOk)
        return false;
      out.emplace_back(std::move(msg));
      return true;
    };
  });
  lcm::LogFile log(path, "r");
  if (!log.good()) throw std::runtime_error("cannot read the LCM log " + path);
  std::vector<RecordedMessage> out;
  LogReadStats counts;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    ++counts.events;
    const auto decoder = decoders.find(e->channel);
    if (decoder == decoders.end()) continue;
    if (decoder->second(*e, out))
      ++counts.used;
    else
      ++counts.rejected;
  }
  if (stats) *stats = counts;
  return out;
}

LogViewer::LogViewer(ScenePlayback& playback, ViewerServer& server)
    : playback_(playback), server_(server) {
  state_.start_utime = playback.startUtime();
  state_.end_utime = playback.endUtime();
  state_.now_utime = playback.nowUtime();
}

SceneMessages LogViewer::snapshot(const std::string& topic) const {
  if (topic == topics::kPlayback)
    return {{topics::kPlayback, state_.now_utime, playbackJson(state_)}};
  return playback_.scene().snapshot(topic);
}

nlohmann::json LogViewer::values() const {
  return nlohmann::json::array({{{"name", "playback.time"}, {"value", state_.now_utime * 1e-6}},
                                {{"name", "playback.playing"}, {"value", state_.playing}},
                                {{"name", "playback.speed"}, {"value", state_.speed}}});
}

nlohmann::json LogViewer::onParameters(const nlohmann::json& parameters) {
  for (const nlohmann::json& p : parameters) {
    const std::string name = p.at("name").get<std::string>();
    const nlohmann::json& value = p.at("value");
    if (name == "playback.time" && value.is_number() && std::isfinite(value.get<double>())) {
      const double t =
          std::clamp(value.get<double>(), state_.start_utime * 1e-6, state_.end_utime * 1e-6);
      seek_pending_ = true;
      seek_utime_ = static_cast<int64_t>(std::llround(t * 1e6));
    } else if (name == "playback.playing" && value.is_boolean()) {
      state_.playing = value.get<bool>();
      // Play at the end of the flight: from its start again.
      if (state_.playing && !seek_pending_ && state_.now_utime >= state_.end_utime) {
        seek_pending_ = true;
        seek_utime_ = state_.start_utime;
      }
      state_changed_ = true;
    } else if (name == "playback.speed" && value.is_number() &&
               std::isfinite(value.get<double>())) {
      state_.speed = std::clamp(value.get<double>(), kMinSpeed, kMaxSpeed);
      state_changed_ = true;
    }
  }
  nlohmann::json out = values();
  if (seek_pending_) out[0]["value"] = seek_utime_ * 1e-6;  // where it is going
  return out;
}

void LogViewer::jump(int64_t utime) {
  playback_.seek(utime);
  state_.now_utime = playback_.nowUtime();
  ++state_.generation;
  // The new generation first: a client drops its scene on it, then the snapshots rebuild it,
  // then "ready" says they are all there.
  state_.ready = false;
  server_.publish({topics::kPlayback, state_.now_utime, playbackJson(state_)});
  server_.resendSnapshots(topics::kPlayback);
  state_.ready = true;
  server_.publish({topics::kPlayback, state_.now_utime, playbackJson(state_)});
  state_changed_ = false;
}

void LogViewer::publishState(int64_t wall_us) {
  server_.publish({topics::kPlayback, state_.now_utime, playbackJson(state_)});
  state_sent_wall_us_ = wall_us;
  state_changed_ = false;
}

void LogViewer::poll(int64_t wall_us) {
  const int64_t elapsed_us = last_wall_us_ > 0 ? std::max<int64_t>(0, wall_us - last_wall_us_) : 0;
  last_wall_us_ = wall_us;
  if (seek_pending_) {
    seek_pending_ = false;
    jump(seek_utime_);
    state_sent_wall_us_ = wall_us;
    return;
  }
  if (state_.playing) {
    const int64_t to = state_.now_utime + static_cast<int64_t>(elapsed_us * state_.speed);
    for (const SceneMessage& m : playback_.advance(to)) server_.publish(m);
    state_.now_utime = playback_.nowUtime();
    if (state_.now_utime >= state_.end_utime) {
      state_.playing = false;
      state_changed_ = true;
    }
    if (wall_us - state_sent_wall_us_ >= kStateEveryUs) state_changed_ = true;
  }
  if (state_changed_) publishState(wall_us);
}

}  // namespace mmh::viewer
