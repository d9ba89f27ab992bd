#include "mmh/viewer/scene_json.hpp"

#include <algorithm>
#include <cmath>

#include "mmh/common/decision_names.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/viewer/polytope_vertices.hpp"

namespace mmh::viewer {
namespace {
using nlohmann::json;

double seconds(int64_t utime) {
  return roundTo(utime * 1e-6, 1e-6);
}
double norm3(const double v[3]) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

const char* awarenessReasonName(int reason) {
  switch (reason) {
    case awareness_t::REASON_CLEAR:
      return "clear";
    case awareness_t::REASON_BLOCKED:
      return "blocked";
    case awareness_t::REASON_NARROW:
      return "narrow";
    default:
      return "?";
  }
}

// values[begin, end) rounded to `step`.
json roundedJson(const std::vector<float>& values, size_t begin, size_t end, double step = 1e-3) {
  json out = json::array();
  for (size_t i = begin; i < end && i < values.size(); ++i) out.push_back(roundTo(values[i], step));
  return out;
}

}  // namespace

double roundTo(double value, double step) {
  return std::round(value / step) * step;
}

json vec3Json(const double v[3], double step) {
  return json::array({roundTo(v[0], step), roundTo(v[1], step), roundTo(v[2], step)});
}

json odometryJson(const odometry_t& msg) {
  return {{"t", seconds(msg.header.utime)},
          {"position", vec3Json(msg.position)},
          {"velocity", vec3Json(msg.velocity)},
          {"acceleration", vec3Json(msg.acceleration)},
          {"orientation",
           json::array({roundTo(msg.orientation[0], 1e-4), roundTo(msg.orientation[1], 1e-4),
                        roundTo(msg.orientation[2], 1e-4), roundTo(msg.orientation[3], 1e-4)})},
          {"speed", roundTo(norm3(msg.velocity), 1e-3)}};
}

json trajectoryJson(const trajectory_t& msg, double sample_s) {
  const Trajectory traj = fromMsg(msg);
  const double duration = traj.duration();
  json points = json::array();
  if (!traj.empty()) {
    const int n = std::max(1, static_cast<int>(std::ceil(duration / sample_s)));
    for (int i = 0; i <= n; ++i) {
      const Eigen::Vector3d p = traj.position(duration * i / n);
      for (int k = 0; k < 3; ++k) points.push_back(roundTo(p[k], 1e-3));
    }
  }
  return {{"t", seconds(msg.header.utime)},
          {"id", msg.trajectory_id},
          {"start_t", seconds(msg.start_utime)},
          {"mode", msg.source_mode},
          {"mode_name", modeName(msg.source_mode)},
          {"duration_s", roundTo(duration, 1e-3)},
          {"pieces", msg.num_pieces},
          {"max_speed", traj.empty() ? 0.0 : roundTo(traj.maxSpeed(), 1e-3)},
          {"points", std::move(points)}};
}

json awarenessJson(const awareness_t& msg) {
  json out = {
      {"t", seconds(msg.header.utime)}, {"safe", msg.safe != 0},
      {"reason", msg.reason},           {"reason_name", awarenessReasonName(msg.reason)},
      {"goal_id", msg.goal_id},         {"position", vec3Json(msg.position)},
      {"goal", vec3Json(msg.goal)},     {"ray_end", vec3Json(msg.ray_end)},
      {"first_blocked", nullptr},       {"compute_ms", roundTo(msg.compute_ns * 1e-6, 1e-4)}};
  if (msg.has_blocked_point) out["first_blocked"] = vec3Json(msg.first_blocked);
  return out;
}

json planRequestJson(const plan_request_t& msg) {
  return {{"t", seconds(msg.header.utime)},
          {"request_id", msg.request_id},
          {"mode", msg.mode},
          {"mode_name", modeName(msg.mode)},
          {"trigger", triggerName(msg.reason)},
          {"start", vec3Json(msg.start_position)},
          {"target", vec3Json(msg.target)},
          {"goal", vec3Json(msg.goal)},
          {"deadline_t", seconds(msg.deadline_utime)}};
}

json planResultJson(const plan_result_t& msg) {
  return {{"t", seconds(msg.header.utime)},
          {"request_id", msg.request_id},
          {"mode", msg.mode},
          {"mode_name", modeName(msg.mode)},
          {"ok", msg.status == plan_result_t::STATUS_OK},
          {"reason", msg.reason},
          {"detail", msg.detail},
          {"compute_ms", roundTo(msg.compute_us * 1e-3, 1e-3)},
          {"narrow", msg.narrow != 0},
          {"cost_total", msg.cost_total}};
}

json decisionJson(const arbiter_status_t& msg) {
  return {{"t", seconds(msg.header.utime)},
          {"seq", msg.decision_seq},
          {"trigger", triggerName(msg.trigger)},
          {"outcome", outcomeName(msg.outcome)},
          {"awareness_safe", msg.awareness_safe != 0},
          {"awareness_reason", awarenessReasonName(msg.awareness_reason)},
          {"modes_asked", modesMaskName(msg.modes_asked)},
          {"modes_answered_ok", modesMaskName(msg.modes_answered_ok)},
          {"committed_mode", modeName(msg.committed_mode)},
          {"request_id", msg.request_id},
          {"trajectory_id", msg.committed_trajectory_id},
          {"compute_ms",
           {{"FPM", roundTo(msg.compute_us_fpm * 1e-3, 1e-3)},
            {"SOM", roundTo(msg.compute_us_som * 1e-3, 1e-3)},
            {"EAM", roundTo(msg.compute_us_eam * 1e-3, 1e-3)}}},
          {"iterations",
           {{"FPM", msg.iterations_fpm}, {"SOM", msg.iterations_som}, {"EAM", msg.iterations_eam}}},
          {"failures", msg.failures},
          {"position", vec3Json(msg.position)},
          {"local_target", vec3Json(msg.local_target)},
          {"detail", msg.detail},
          // From the scan that showed the danger this decision answers; -1: it answers none.
          {"reaction_ms", msg.threat_seen_utime > 0
                              ? roundTo((msg.header.utime - msg.threat_seen_utime) * 1e-3, 1e-3)
                              : -1.0}};
}

json heartbeatJson(const heartbeat_t& msg) {
  json counters = json::object();
  for (int i = 0; i < msg.num_counters; ++i) counters[msg.counter_names[i]] = msg.counter_values[i];
  return {{"t", seconds(msg.header.utime)},
          {"service", msg.service},
          {"host", msg.host},
          {"pid", msg.pid},
          {"state", heartbeatStateName(msg.state)},
          {"detail", msg.state_detail},
          {"uptime_s", msg.uptime_s},
          {"msgs_in", msg.msgs_in},
          {"msgs_out", msg.msgs_out},
          {"msgs_rejected", msg.msgs_rejected},
          {"counters", std::move(counters)}};
}

json missionJson(const mission_status_t& msg) {
  return {{"t", seconds(msg.header.utime)},
          {"active", msg.active != 0},
          {"reached", msg.reached != 0},
          {"collided", msg.collided != 0},
          {"flight_time_s", roundTo(msg.flight_time_s, 1e-3)},
          {"distance_m", roundTo(msg.distance_m, 1e-3)},
          {"energy", roundTo(msg.energy, 1e-3)},
          {"position", vec3Json(msg.position)},
          {"goal", vec3Json(msg.goal)},
          {"min_clearance_m", roundTo(msg.min_clearance_m, 1e-3)}};
}

json voxelsJson(const VoxelChanges& changes, double resolution_m, bool snapshot) {
  return {{"snapshot", snapshot},
          {"resolution", resolution_m},
          {"added", changes.added},
          {"removed", changes.removed}};
}

json pathJson(const std::vector<PathSample>& samples, bool snapshot) {
  json t = json::array(), xyz = json::array(), speed = json::array(), acc = json::array();
  for (const PathSample& s : samples) {
    t.push_back(roundTo(s.t_s, 1e-3));
    for (double v : s.position) xyz.push_back(roundTo(v, 1e-3));
    speed.push_back(roundTo(s.speed_mps, 1e-3));
    acc.push_back(roundTo(s.acceleration_mps2, 1e-3));
  }
  return {{"snapshot", snapshot},
          {"t", std::move(t)},
          {"points", std::move(xyz)},
          {"speed", std::move(speed)},
          {"acceleration", std::move(acc)}};
}

json planDebugJson(const plan_debug_t& msg) {
  json paths = json::array();
  size_t at = 0;
  for (int32_t n : msg.path_points) {
    const size_t end = at + 3 * static_cast<size_t>(n);
    paths.push_back(roundedJson(msg.path_xyz, at, end));
    at = end;
  }
  json polytopes = json::array();
  at = 0;
  for (int32_t n : msg.polytope_faces) {
    std::vector<Eigen::Vector4d> faces;
    for (int32_t f = 0; f < n && at + 4 <= msg.faces.size(); ++f, at += 4)
      faces.emplace_back(msg.faces[at], msg.faces[at + 1], msg.faces[at + 2], msg.faces[at + 3]);
    json vertices = json::array();
    for (const Eigen::Vector3d& v : polytopeVertices(faces))
      for (int k = 0; k < 3; ++k) vertices.push_back(roundTo(v[k], 1e-3));
    polytopes.push_back(std::move(vertices));
  }
  return {{"t", seconds(msg.header.utime)},
          {"request_id", msg.request_id},
          {"mode", msg.mode},
          {"mode_name", modeName(msg.mode)},
          {"ok", msg.ok != 0},
          {"paths", std::move(paths)},
          {"polytopes", std::move(polytopes)},
          {"control_points", roundedJson(msg.control_xyz, 0, msg.control_xyz.size())},
          {"pair_control_point", msg.pair_control_point},
          {"pair_p", roundedJson(msg.pair_p, 0, msg.pair_p.size())},
          {"pair_v", roundedJson(msg.pair_v, 0, msg.pair_v.size(), 1e-4)}};
}

json playbackJson(const PlaybackState& state) {
  return {{"t", seconds(state.now_utime)},
          {"start_t", seconds(state.start_utime)},
          {"end_t", seconds(state.end_utime)},
          {"playing", state.playing},
          {"speed", state.speed},
          {"generation", state.generation},
          {"ready", state.ready}};
}

}  // namespace mmh::viewer
