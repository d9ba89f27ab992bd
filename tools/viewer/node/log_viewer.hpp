// mmh-viewer --log FILE: a recorded flight served with a time slider. The vehicle's channels of
// the LCM log are read (each message decoded and validated as a live one would be) into a
// ScenePlayback; the page (or any Foxglove client) drives it with the protocol's parameters
// playback.time (s of the message clock), playback.playing and playback.speed, and sees where
// it is on /mmh/playback.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mmh/viewer/scene_json.hpp"
#include "mmh/viewer/scene_playback.hpp"
#include "viewer_server.hpp"

namespace mmh::viewer {

struct LogReadStats {
  int64_t events = 0;    // in the file
  int64_t used = 0;      // on the scene's channels, decoded and valid
  int64_t rejected = 0;  // on the scene's channels, but undecodable or invalid
};

// The scene's messages of `prefix` in the log, in log order. Throws std::runtime_error if the
// file cannot be read.
std::vector<RecordedMessage> readFlightLog(const std::string& path, const std::string& prefix,
                                           LogReadStats* stats);

class LogViewer {
 public:
  LogViewer(ScenePlayback& playback, ViewerServer& server);

  // The server's snapshot source: the scene at the current time, and /mmh/playback.
  SceneMessages snapshot(const std::string& topic) const;
  // The server's parameter handler: takes playback.* settings (a jump waits for poll()).
  nlohmann::json onParameters(const nlohmann::json& parameters);
  // Does what the parameters asked and, while playing, plays on by the wall time since the last
  // call times the speed; sends the scene messages, and after a jump the new snapshots.
  void poll(int64_t wall_us);
  const PlaybackState& state() const { return state_; }

 private:
  void jump(int64_t utime);
  void publishState(int64_t wall_us);
  nlohmann::json values() const;

  ScenePlayback& playback_;
  ViewerServer& server_;
  PlaybackState state_;
  bool seek_pending_ = false;
  int64_t seek_utime_ = 0;
  bool state_changed_ = true;
  int64_t last_wall_us_ = 0, state_sent_wall_us_ = 0;
};

}  // namespace mmh::viewer
