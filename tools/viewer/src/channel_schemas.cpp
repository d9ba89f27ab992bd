#include "mmh/viewer/channel_schemas.hpp"

#include "mmh/viewer/scene_topics.hpp"

namespace mmh::viewer {
namespace {
using nlohmann::json;

json number() {
  return {{"type", "number"}};
}
json integer() {
  return {{"type", "integer"}};
}
json boolean() {
  return {{"type", "boolean"}};
}
json text() {
  return {{"type", "string"}};
}
json arrayOf(const json& items) {
  return {{"type", "array"}, {"items", items}};
}
json vec3() {
  return {{"type", "array"}, {"items", number()}, {"minItems", 3}, {"maxItems", 3}};
}
json nullableVec3() {
  return {{"type", {"array", "null"}}, {"items", number()}};
}

// An object whose listed properties are all required.
json object(const std::string& title, const json& properties) {
  json required = json::array();
  for (auto it = properties.begin(); it != properties.end(); ++it) required.push_back(it.key());
  return {{"title", title},
          {"type", "object"},
          {"properties", properties},
          {"required", std::move(required)}};
}

json byMode(const json& value) {
  return object("per mode", {{"FPM", value}, {"SOM", value}, {"EAM", value}});
}
}  // namespace

std::vector<ChannelInfo> viewerChannels(bool with_playback) {
  std::vector<ChannelInfo> out = {
      {0, topics::kMapVoxels, "mmh.viewer.MapVoxels",
       object("occupied voxels added and removed (global voxel indices, flattened x, y, z; a "
              "voxel's centre is (index + 0.5) * resolution)",
              {{"snapshot", boolean()},
               {"resolution", number()},
               {"added", arrayOf(integer())},
               {"removed", arrayOf(integer())}})},
      {0, topics::kOdometry, "mmh.viewer.Odometry",
       object("vehicle state (world frame; t in s of the message clock)",
              {{"t", number()},
               {"position", vec3()},
               {"velocity", vec3()},
               {"acceleration", vec3()},
               {"orientation", arrayOf(number())},
               {"speed", number()}})},
      {0, topics::kFlownPath, "mmh.viewer.FlownPath",
       object("path samples (points flattened x, y, z)", {{"snapshot", boolean()},
                                                          {"t", arrayOf(number())},
                                                          {"points", arrayOf(number())},
                                                          {"speed", arrayOf(number())},
                                                          {"acceleration", arrayOf(number())}})},
      {0, topics::kTrajectory, "mmh.viewer.Trajectory",
       object("a committed trajectory, sampled (points flattened x, y, z)",
              {{"t", number()},
               {"id", integer()},
               {"start_t", number()},
               {"mode", integer()},
               {"mode_name", text()},
               {"duration_s", number()},
               {"pieces", integer()},
               {"max_speed", number()},
               {"points", arrayOf(number())}})},
      {0, topics::kAwareness, "mmh.viewer.Awareness",
       object("goal-oriented spatial awareness", {{"t", number()},
                                                  {"safe", boolean()},
                                                  {"reason", integer()},
                                                  {"reason_name", text()},
                                                  {"goal_id", integer()},
                                                  {"position", vec3()},
                                                  {"goal", vec3()},
                                                  {"ray_end", vec3()},
                                                  {"first_blocked", nullableVec3()},
                                                  {"compute_ms", number()}})},
      {0, topics::kPlanRequest, "mmh.viewer.PlanRequest",
       object("a request to a mode", {{"t", number()},
                                      {"request_id", integer()},
                                      {"mode", integer()},
                                      {"mode_name", text()},
                                      {"trigger", text()},
                                      {"start", vec3()},
                                      {"target", vec3()},
                                      {"goal", vec3()},
                                      {"deadline_t", number()}})},
      {0, topics::kPlanResult, "mmh.viewer.PlanResult",
       object("a mode's answer", {{"t", number()},
                                  {"request_id", integer()},
                                  {"mode", integer()},
                                  {"mode_name", text()},
                                  {"ok", boolean()},
                                  {"reason", integer()},
                                  {"detail", text()},
                                  {"compute_ms", number()},
                                  {"narrow", boolean()},
                                  {"cost_total", number()}})},
      {0, topics::kDecision, "mmh.viewer.Decision",
       object("one arbiter decision (ARBITER_STATUS)", {{"t", number()},
                                                        {"seq", integer()},
                                                        {"trigger", text()},
                                                        {"outcome", text()},
                                                        {"awareness_safe", boolean()},
                                                        {"awareness_reason", text()},
                                                        {"modes_asked", text()},
                                                        {"modes_answered_ok", text()},
                                                        {"committed_mode", text()},
                                                        {"request_id", integer()},
                                                        {"trajectory_id", integer()},
                                                        {"compute_ms", byMode(number())},
                                                        {"iterations", byMode(integer())},
                                                        {"failures", integer()},
                                                        {"position", vec3()},
                                                        {"local_target", vec3()},
                                                        {"detail", text()},
                                                        {"reaction_ms", number()}})},
      {0, topics::kHeartbeat, "mmh.viewer.Heartbeat",
       object("a service's HEARTBEAT",
              {{"t", number()},
               {"service", text()},
               {"host", text()},
               {"pid", integer()},
               {"state", text()},
               {"detail", text()},
               {"uptime_s", integer()},
               {"msgs_in", integer()},
               {"msgs_out", integer()},
               {"msgs_rejected", integer()},
               {"counters", {{"type", "object"}, {"additionalProperties", integer()}}}})},
      {0, topics::kMission, "mmh.viewer.Mission",
       object("the simulator's ground truth (MISSION_STATUS)", {{"t", number()},
                                                                {"active", boolean()},
                                                                {"reached", boolean()},
                                                                {"collided", boolean()},
                                                                {"flight_time_s", number()},
                                                                {"distance_m", number()},
                                                                {"energy", number()},
                                                                {"position", vec3()},
                                                                {"goal", vec3()},
                                                                {"min_clearance_m", number()}})},
      {0, topics::kPlanDebug, "mmh.viewer.PlanDebug",
       object("what SOM or EAM computed for one answer (PLAN_DEBUG; flattened x, y, z): A* paths "
              "(SOM's path, EAM's guides), SOM's corridor polytopes as vertices, EAM's control "
              "points and {p, v} pairs (pair i: control point pair_control_point[i], plane "
              "through p with normal v)",
              {{"t", number()},
               {"request_id", integer()},
               {"mode", integer()},
               {"mode_name", text()},
               {"ok", boolean()},
               {"paths", arrayOf(arrayOf(number()))},
               {"polytopes", arrayOf(arrayOf(number()))},
               {"control_points", arrayOf(number())},
               {"pair_control_point", arrayOf(integer())},
               {"pair_p", arrayOf(number())},
               {"pair_v", arrayOf(number())}})},
  };
  if (with_playback) {
    out.push_back({0, topics::kPlayback, "mmh.viewer.Playback",
                   object("mmh-viewer --log: the time shown of the recorded flight (set with the "
                          "parameters playback.time, playback.playing, playback.speed)",
                          {{"t", number()},
                           {"start_t", number()},
                           {"end_t", number()},
                           {"playing", boolean()},
                           {"speed", number()},
                           {"generation", integer()},
                           {"ready", boolean()}})});
  }
  for (size_t i = 0; i < out.size(); ++i) out[i].id = static_cast<uint32_t>(i + 1);
  return out;
}

}  // namespace mmh::viewer
