// The debug layer's encoding (PLAN_DEBUG to the page: polytopes as vertices, paths split, pairs
// with their control points) and the Foxglove parameters that drive mmh-viewer --log.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "mmh/common/message_validation.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/viewer/foxglove_protocol.hpp"
#include "mmh/viewer/polytope_vertices.hpp"
#include "mmh/viewer/scene_json.hpp"

namespace mmh::viewer {
namespace {
using nlohmann::json;

// The box [lo, hi] as faces a . x <= b.
std::vector<Eigen::Vector4d> boxFaces(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  std::vector<Eigen::Vector4d> faces;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector4d up = Eigen::Vector4d::Zero(), down = Eigen::Vector4d::Zero();
    up[k] = 1.0;
    up[3] = hi[k];
    down[k] = -1.0;
    down[3] = -lo[k];
    faces.push_back(up);
    faces.push_back(down);
  }
  return faces;
}

Eigen::Matrix<double, Eigen::Dynamic, 4> asMatrix(const std::vector<Eigen::Vector4d>& faces) {
  Eigen::Matrix<double, Eigen::Dynamic, 4> h(faces.size(), 4);
  for (size_t i = 0; i < faces.size(); ++i) h.row(i) = faces[i].transpose();
  return h;
}

TEST(PolytopeVertices, ABoxHasItsEightCornersOnce) {
  std::vector<Eigen::Vector4d> faces = boxFaces({0, 0, 0}, {2, 1, 3});
  faces.push_back(Eigen::Vector4d(1, 0, 0, 5));  // redundant: cuts nothing
  const std::vector<Eigen::Vector3d> v = polytopeVertices(faces);
  ASSERT_EQ(v.size(), 8u);
  for (const Eigen::Vector3d& corner : v) {
    for (int k = 0; k < 3; ++k)
      EXPECT_TRUE(corner[k] == 0.0 || corner[k] == Eigen::Vector3d(2, 1, 3)[k]);
  }
}

TEST(PolytopeVertices, ACutCornerAddsVerticesAndAnEmptySetHasNone) {
  std::vector<Eigen::Vector4d> faces = boxFaces({0, 0, 0}, {1, 1, 1});
  faces.push_back(Eigen::Vector4d(1, 1, 1, 2.5) / std::sqrt(3.0));  // x + y + z <= 2.5
  EXPECT_EQ(polytopeVertices(faces).size(), 10u);  // corner (1,1,1) becomes a triangle
  std::vector<Eigen::Vector4d> empty = boxFaces({0, 0, 0}, {1, 1, 1});
  empty.push_back(Eigen::Vector4d(1, 0, 0, -1));  // x <= -1
  EXPECT_TRUE(polytopeVertices(empty).empty());
}

TEST(PlanDebugJson, PolytopesBecomeVerticesAndPathsAndPairsKeepTheirParts) {
  PlanDebug debug;
  debug.paths = {{Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1.23456, 0, 1)},
                 {Eigen::Vector3d(2, 2, 2), Eigen::Vector3d(3, 2, 2), Eigen::Vector3d(4, 2, 2)}};
  debug.polytopes = {asMatrix(boxFaces({0, 0, 0}, {1, 1, 1})),
                     asMatrix(boxFaces({1, 0, 0}, {3, 1, 2}))};
  debug.control_points = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                          Eigen::Vector3d(2, 0, 0)};
  debug.pairs = {{1, Eigen::Vector3d(1, 0.5, 0), Eigen::Vector3d(0, -1, 0)},
                 {2, Eigen::Vector3d(2, 0.5, 0), Eigen::Vector3d(0, -0.6, 0.8)}};
  plan_debug_t msg = toDebugMsg(debug, 42, plan_request_t::MODE_SOM, true);
  msg.header.utime = 2'500'000;
  std::string why;
  ASSERT_TRUE(validate(msg, &why)) << why;

  const json j = planDebugJson(msg);
  EXPECT_EQ(j["request_id"], 42);
  EXPECT_EQ(j["mode_name"], "SOM");
  EXPECT_TRUE(j["ok"].get<bool>());
  EXPECT_DOUBLE_EQ(j["t"].get<double>(), 2.5);
  ASSERT_EQ(j["paths"].size(), 2u);
  EXPECT_EQ(j["paths"][0].size(), 6u);
  EXPECT_EQ(j["paths"][1].size(), 9u);
  EXPECT_DOUBLE_EQ(j["paths"][0][3].get<double>(), 1.235);  // rounded to the millimetre
  ASSERT_EQ(j["polytopes"].size(), 2u);
  EXPECT_EQ(j["polytopes"][0].size(), 24u);  // 8 corners
  EXPECT_EQ(j["polytopes"][1].size(), 24u);
  double max_x = 0.0;
  for (size_t i = 0; i < j["polytopes"][1].size(); i += 3)
    max_x = std::max(max_x, j["polytopes"][1][i].get<double>());
  EXPECT_DOUBLE_EQ(max_x, 3.0);
  EXPECT_EQ(j["control_points"].size(), 9u);
  EXPECT_EQ(j["pair_control_point"], json::array({1, 2}));
  EXPECT_EQ(j["pair_p"].size(), 6u);
  EXPECT_DOUBLE_EQ(j["pair_v"][4].get<double>(), -0.6);
}

TEST(FoxgloveParameters, SetAndGetParametersAreParsedAndAnswered) {
  using foxglove::ClientRequest;
  ClientRequest set = foxglove::parseClientRequest(
      R"({"op":"setParameters","id":"s1","parameters":[{"name":"playback.time","value":12.5},)"
      R"({"name":"playback.playing","value":true}]})");
  ASSERT_EQ(set.kind, ClientRequest::Kind::kSetParameters);
  EXPECT_EQ(set.id, "s1");
  ASSERT_EQ(set.parameters.size(), 2u);
  EXPECT_EQ(set.parameters[0]["name"], "playback.time");
  EXPECT_DOUBLE_EQ(set.parameters[0]["value"].get<double>(), 12.5);
  const ClientRequest get =
      foxglove::parseClientRequest(R"({"op":"getParameters","parameterNames":[]})");
  EXPECT_EQ(get.kind, ClientRequest::Kind::kGetParameters);
  EXPECT_TRUE(get.id.empty());
  EXPECT_EQ(
      foxglove::parseClientRequest(R"({"op":"setParameters","parameters":[{"value":1}]})").kind,
      ClientRequest::Kind::kMalformed);
  const json answer = json::parse(foxglove::parameterValues(set.parameters, "s1"));
  EXPECT_EQ(answer["op"], "parameterValues");
  EXPECT_EQ(answer["id"], "s1");
  EXPECT_EQ(answer["parameters"].size(), 2u);
  const json info = json::parse(foxglove::serverInfo("mmh-viewer", "1", {"parameters"}));
  EXPECT_EQ(info["capabilities"], json::array({"parameters"}));
  EXPECT_EQ(json::parse(foxglove::serverInfo("mmh-viewer", "1"))["capabilities"], json::array());
}

TEST(PlaybackJson, SaysWhereTheSliderIs) {
  PlaybackState state;
  state.start_utime = 1'000'000;
  state.end_utime = 21'500'000;
  state.now_utime = 7'250'000;
  state.playing = true;
  state.speed = 2.0;
  state.generation = 3;
  const json j = playbackJson(state);
  EXPECT_DOUBLE_EQ(j["t"].get<double>(), 7.25);
  EXPECT_DOUBLE_EQ(j["start_t"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(j["end_t"].get<double>(), 21.5);
  EXPECT_TRUE(j["playing"].get<bool>());
  EXPECT_EQ(j["generation"], 3);
}

}  // namespace
}  // namespace mmh::viewer
