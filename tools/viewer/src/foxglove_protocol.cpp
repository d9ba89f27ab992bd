#include "mmh/viewer/foxglove_protocol.hpp"

#include <nlohmann/json.hpp>

namespace mmh::viewer::foxglove {
namespace {
using nlohmann::json;

void appendLittleEndian(std::string& out, uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xff));
}

uint32_t idOf(const json& value) {
  if (!value.is_number_unsigned()) throw std::invalid_argument("ids must be unsigned integers");
  const uint64_t id = value.get<uint64_t>();
  if (id > UINT32_MAX) throw std::invalid_argument("id out of range");
  return static_cast<uint32_t>(id);
}
}  // namespace

std::string serverInfo(const std::string& server_name, const std::string& session_id,
                       const std::vector<std::string>& capabilities) {
  return json{{"op", "serverInfo"},           {"name", server_name},
              {"capabilities", capabilities}, {"supportedEncodings", json::array({"json"})},
              {"metadata", json::object()},   {"sessionId", session_id}}
      .dump();
}

std::string advertise(const std::vector<ChannelInfo>& channels) {
  json list = json::array();
  for (const ChannelInfo& c : channels)
    list.push_back({{"id", c.id},
                    {"topic", c.topic},
                    {"encoding", "json"},
                    {"schemaName", c.schema_name},
                    {"schema", c.schema.dump()},
                    {"schemaEncoding", "jsonschema"}});
  return json{{"op", "advertise"}, {"channels", std::move(list)}}.dump();
}

std::string status(StatusLevel level, const std::string& message) {
  return json{{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}}.dump();
}

std::string messageData(uint32_t subscription_id, uint64_t timestamp_ns,
                        const std::string& payload) {
  std::string frame;
  frame.reserve(13 + payload.size());
  frame.push_back(0x01);
  appendLittleEndian(frame, subscription_id, 4);
  appendLittleEndian(frame, timestamp_ns, 8);
  frame += payload;
  return frame;
}

std::string parameterValues(const json& parameters, const std::string& id) {
  json out = {{"op", "parameterValues"}, {"parameters", parameters}};
  if (!id.empty()) out["id"] = id;
  return out.dump();
}

ClientRequest parseClientRequest(const std::string& text) {
  ClientRequest request;
  try {
    const json j = json::parse(text);
    const std::string op = j.at("op").get<std::string>();
    if (op == "subscribe") {
      request.kind = ClientRequest::Kind::kSubscribe;
      for (const json& s : j.at("subscriptions"))
        request.subscriptions.emplace_back(idOf(s.at("id")), idOf(s.at("channelId")));
    } else if (op == "unsubscribe") {
      request.kind = ClientRequest::Kind::kUnsubscribe;
      for (const json& id : j.at("subscriptionIds")) request.unsubscribed.push_back(idOf(id));
    } else if (op == "setParameters" || op == "getParameters") {
      request.kind = op == "setParameters" ? ClientRequest::Kind::kSetParameters
                                           : ClientRequest::Kind::kGetParameters;
      if (j.contains("id")) request.id = j.at("id").get<std::string>();
      if (request.kind == ClientRequest::Kind::kSetParameters) {
        for (const json& p : j.at("parameters")) {
          p.at("name").get<std::string>();  // throws unless a name is given
          request.parameters.push_back(
              {{"name", p.at("name")}, {"value", p.value("value", json())}});
        }
      }
    }
  } catch (const std::exception& e) {
    request = ClientRequest{};
    request.kind = ClientRequest::Kind::kMalformed;
    request.error = e.what();
  }
  return request;
}

}  // namespace mmh::viewer::foxglove
