// The server side of the Foxglove WebSocket protocol (foxglove.websocket.v1) as far as the viewer
// speaks it: serverInfo, advertise and status text frames, binary message-data frames, and the
// client's subscribe / unsubscribe requests. Only text and bytes here; the socket is elsewhere.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "mmh/viewer/channel_schemas.hpp"

namespace mmh::viewer::foxglove {

inline constexpr const char* kSubprotocol = "foxglove.websocket.v1";

// capabilities: e.g. {"parameters"} (mmh-viewer --log: the playback parameters).
std::string serverInfo(const std::string& server_name, const std::string& session_id,
                       const std::vector<std::string>& capabilities = {});
std::string advertise(const std::vector<ChannelInfo>& channels);
enum class StatusLevel { kInfo = 0, kWarning = 1, kError = 2 };
std::string status(StatusLevel level, const std::string& message);

// Opcode 0x01, subscription id (uint32 LE), receive timestamp in ns (uint64 LE), payload.
std::string messageData(uint32_t subscription_id, uint64_t timestamp_ns,
                        const std::string& payload);

// The parameterValues answer to getParameters / setParameters: parameters is a JSON array of
// {"name", "value"} objects; id is the request's (empty: none).
std::string parameterValues(const nlohmann::json& parameters, const std::string& id);

struct ClientRequest {
  enum class Kind {
    kSubscribe,
    kUnsubscribe,
    kSetParameters,
    kGetParameters,
    kIgnored,
    kMalformed
  };
  Kind kind = Kind::kIgnored;
  std::vector<std::pair<uint32_t, uint32_t>> subscriptions;  // (subscription id, channel id)
  std::vector<uint32_t> unsubscribed;                        // subscription ids
  nlohmann::json parameters = nlohmann::json::array();       // kSetParameters: {name, value}
  std::string id;                                            // kSet/GetParameters' id, if any
  std::string error;                                         // kMalformed: why
};

// A text frame from a client. Operations the viewer does not offer (advertise, publish, …) are
// kIgnored.
ClientRequest parseClientRequest(const std::string& text);

}  // namespace mmh::viewer::foxglove
