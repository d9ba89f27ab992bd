#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "mmh/viewer/foxglove_protocol.hpp"

namespace mmh::viewer::foxglove {
namespace {
using nlohmann::json;

TEST(FoxgloveProtocol, ServerInfoAndAdvertise) {
  const json info = json::parse(serverInfo("mmh-viewer", "7"));
  EXPECT_EQ(info["op"], "serverInfo");
  EXPECT_EQ(info["supportedEncodings"], json::array({"json"}));
  EXPECT_EQ(info["sessionId"], "7");
  const json ad = json::parse(advertise(viewerChannels()));
  EXPECT_EQ(ad["op"], "advertise");
  ASSERT_EQ(ad["channels"].size(), 11u);
  const json& first = ad["channels"][0];
  EXPECT_EQ(first["id"], 1);
  EXPECT_EQ(first["topic"], "/mmh/map_voxels");
  EXPECT_EQ(first["encoding"], "json");
  EXPECT_EQ(first["schemaEncoding"], "jsonschema");
  EXPECT_EQ(json::parse(first["schema"].get<std::string>())["type"], "object");
}

TEST(FoxgloveProtocol, MessageDataFrameIsLittleEndian) {
  const std::string frame = messageData(0x01020304, 0x1122334455667788ull, "{}");
  ASSERT_EQ(frame.size(), 15u);
  EXPECT_EQ(frame[0], 0x01);
  EXPECT_EQ(frame.substr(1, 4), std::string("\x04\x03\x02\x01", 4));
  EXPECT_EQ(frame.substr(5, 8), std::string("\x88\x77\x66\x55\x44\x33\x22\x11", 8));
  EXPECT_EQ(frame.substr(13), "{}");
}

TEST(FoxgloveProtocol, SubscribeAndUnsubscribe) {
  const ClientRequest sub = parseClientRequest(
      R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":3},{"id":1,"channelId":4}]})");
  ASSERT_EQ(sub.kind, ClientRequest::Kind::kSubscribe);
  EXPECT_EQ(sub.subscriptions, (std::vector<std::pair<uint32_t, uint32_t>>{{0, 3}, {1, 4}}));
  const ClientRequest unsub = parseClientRequest(R"({"op":"unsubscribe","subscriptionIds":[1]})");
  ASSERT_EQ(unsub.kind, ClientRequest::Kind::kUnsubscribe);
  EXPECT_EQ(unsub.unsubscribed, std::vector<uint32_t>{1});
  EXPECT_EQ(parseClientRequest(R"({"op":"advertise","channels":[]})").kind,
            ClientRequest::Kind::kIgnored);
}

TEST(FoxgloveProtocol, MalformedRequestsAreReportedNotThrown) {
  for (const char* text :
       {"not json", "[]", R"({"op":"subscribe"})",
        R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":1}]})",
        R"({"op":"subscribe","subscriptions":[{"id":5000000000,"channelId":1}]})",
        R"({"op":"unsubscribe","subscriptionIds":["a"]})"}) {
    const ClientRequest r = parseClientRequest(text);
    EXPECT_EQ(r.kind, ClientRequest::Kind::kMalformed) << text;
    EXPECT_FALSE(r.error.empty()) << text;
  }
}

TEST(FoxgloveProtocol, StatusMessage) {
  const json s = json::parse(status(StatusLevel::kWarning, "no channel 99"));
  EXPECT_EQ(s["op"], "status");
  EXPECT_EQ(s["level"], 1);
  EXPECT_EQ(s["message"], "no channel 99");
}

}  // namespace
}  // namespace mmh::viewer::foxglove
