// The viewer's channels as advertised to Foxglove WebSocket clients: topic, schema name and the
// JSON Schema of the messages that scene_json.hpp writes.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace mmh::viewer {

struct ChannelInfo {
  uint32_t id = 0;
  std::string topic;
  std::string schema_name;
  nlohmann::json schema;
};

// Every channel, ids from 1 in the order of scene_topics.hpp; /mmh/playback only with_playback
// (mmh-viewer --log).
std::vector<ChannelInfo> viewerChannels(bool with_playback = false);

}  // namespace mmh::viewer
