#include "mmh/common/message_validation.hpp"

#include <cmath>
#include <vector>

#include "mmh/common/local_map_codec.hpp"

namespace mmh {
namespace {

bool fail(std::string* why, const std::string& text) {
  if (why) *why = text;
  return false;
}

bool finiteVec(const double* v, int n, double bound = kMaxAbsCoordinate_m) {
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(v[i]) || std::abs(v[i]) > bound) return false;
  }
  return true;
}

// LCM strings end at the first NUL when encoded but not when sized: a string holding one would be
// re-published shorter than its size, with uninitialised bytes after it. Identifiers (service
// names, hosts, counter names) must also be free of control characters, which would forge lines
// or terminal escapes in logs and in mmh-top.
bool validText(const std::string& s, size_t max_length) {
  return s.size() <= max_length && s.find('\0') == std::string::npos;
}

bool validIdentifier(const std::string& s) {
  if (s.size() > 256) return false;
  for (char c : s) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return false;
  }
  return true;
}

bool finiteFloats(const std::vector<float>& v) {
  for (float x : v) {
    if (!std::isfinite(x) || std::abs(x) > kMaxAbsCoordinate_m) return false;
  }
  return true;
}

// A count field that agrees with its array, within kMaxDebugValues.
template <class T>
bool sized(int32_t n, const std::vector<T>& values) {
  return n >= 0 && n <= kMaxDebugValues && static_cast<size_t>(n) == values.size();
}

// Counts that split `total` values into groups of `per` values times each count.
bool partitions(const std::vector<int32_t>& counts, int per, size_t total) {
  int64_t sum = 0;
  for (int32_t n : counts) {
    if (n < 0) return false;
    sum += n;
  }
  return sum * per == static_cast<int64_t>(total);
}

bool validQuaternion(const double* q) {
  if (!finiteVec(q, 4, 2.0)) return false;
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  return std::abs(n - 1.0) < 1e-2;
}

}  // namespace

bool validate(const header_t& msg, std::string* why) {
  if (msg.utime < 0) return fail(why, "header.utime is negative");
  if (msg.utime > kMaxUtime_us) return fail(why, "header.utime is absurdly far in the future");
  if (msg.seq < 0) return fail(why, "header.seq is negative");
  if (msg.source.size() > 256) return fail(why, "header.source is too long");
  if (!validIdentifier(msg.source)) return fail(why, "header.source has control characters");
  return true;
}

bool validate(const odometry_t& msg, std::string* why) {
  if (!validate(msg.header, why)) return false;
  if (!finiteVec(msg.position, 3)) return fail(why, "position is not finite");
  if (!finiteVec(msg.velocity, 3, 1e3)) return fail(why, "velocity is not finite or absurd");
  if (!finiteVec(msg.acceleration, 3, 1e4))
    return fail(why, "acceleration is not finite or absurd");
  if (!validQuaternion(msg.orientation)) return fail(why, "orientation is not a unit quaternion");
  return true;
}

bool validate(const pointcloud_t& msg, std::string* why) {
  if (!validate(msg.header, why)) return false;
  if (msg.sensor_kind != pointcloud_t::SENSOR_DEPTH &&
      msg.sensor_kind != pointcloud_t::SENSOR_LIDAR)
    return fail(why, "unknown sensor_kind " + std::to_string(msg.sensor_kind));
  if (!finiteVec(msg.sensor_position, 3)) return fail(why, "sensor_position is not finite");
  if (!validQuaternion(msg.sensor_orientation))
    return fail(why, "sensor_orientation is not a unit quaternion");
  if (!std::isfinite(msg.max_range_m) || msg.max_range_m <= 0.f || msg.max_range_m > 1000.f)
    return fail(why, "max_range_m outside (0, 1000]");
  if (msg.num_coords < 0 || static_cast<size_t>(msg.num_coords) != msg.xyz.size())
    return fail(why, "num_coords disagrees with the data");
  if (msg.num_coords % 3 != 0) return fail(why, "num_coords is not a multiple of 3");
  if (msg.num_coords > kMaxPointcloudCoords) return fail(why, "scan has too many points");
  return true;
}

bool validate(const goal_t& msg, std::string* why) {
  if (!validate(msg.header, why)) return false;
  if (msg.goal_id < 0) return fail(why, "goal_id is negative");
  if (!finiteVec(msg.position, 3)) return fail(why, "goal position is not finite");
  if (msg.num_waypoints < 0 || msg.num_waypoints > kMaxWaypoints)
    return fail(why, "num_waypoints outside [0, " + std::to_string(kMaxWaypoints) + "]");
  if (msg.waypoint_index < 0 || (msg.num_waypoints > 0 && msg.waypoint_index >= msg.num_waypoints))
    return fail(why, "waypoint_index outside the mission");
  if (!std::isfinite(msg.tolerance_m) || msg.tolerance_m < 0.0 || msg.tolerance_m > 1e3)
    return fail(why, "tolerance_m is not in [0, 1000] m");
  return true;
}

bool validate(const local_map_t& msg, std::string* why) {
  if (!validate(msg.header, why)) return false;
  if (msg.num_changed < 0) return fail(why, "num_changed is negative");
  return validateLocalMap(msg, why);
}

bool validate(const awareness_t& msg, std::string* why) {
  if (!validate(msg.header, why)) return false;
  if (msg.reason < awareness_t::REASON_CLEAR || msg.reason > awareness_t::REASON_NARROW)
    return fail(why, "unknown awareness reason");
  if (!finiteVec(msg.position, 3) || !finiteVec(msg.goal, 3) || !finiteVec(msg.ray_end, 3) ||
      !finiteVec(msg.first_blocked, 3))
    return fail(why, "awareness has non-finite coordinates");
  return true;
}

bool validate(const trajectory_t& msg, std::string* why) {
  if (!validate(msg.header, why)) return false;
  if (msg.num_pieces < 0 || static_cast<size_t>(msg.num_pieces) != msg.pieces.size())
    return fail(why, "num_pieces disagrees with the data");
  if (msg.num_pieces > kMaxTrajectoryPieces) return fail(why, "trajectory has too many pieces");
  if (msg.start_utime < 0 || msg.start_utime > kMaxUtime_us)
    return fail(why, "start_utime is negative or absurd");
  if (msg.source_mode < 0 || msg.source_mode > plan_request_t::MODE_STOP)
    return fail(why, "unknown source_mode " + std::to_string(msg.source_mode));
  double total_s = 0.0;
  for (const traj_piece_t& p : msg.pieces) {
    if (!std::isfinite(p.duration_s) || p.duration_s <= 0.0 || p.duration_s > 1e4)
      return fail(why, "piece duration outside (0, 1e4] s");
    total_s += p.duration_s;
    if (total_s > kMaxTrajectoryDuration_s) return fail(why, "trajectory lasts more than an hour");
    for (int a = 0; a < 3; ++a) {
      if (!finiteVec(p.coeffs[a], 8, 1e12)) return fail(why, "piece coefficient not finite");
    }
  }
  return true;
}

bool validate(const plan_request_t& msg, std::string* why) {
  if (!validate(msg.header, why)) return false;
  if (msg.mode < plan_request_t::MODE_FPM || msg.mode > plan_request_t::MODE_STOP)
    return fail(why, "unknown mode " + std::to_string(msg.mode));
  if (!finiteVec(msg.start_position, 3) || !finiteVec(msg.start_velocity, 3, 1e3) ||
      !finiteVec(msg.start_acceleration, 3, 1e4))
    return fail(why, "start state is not finite or absurd");
  if (!finiteVec(msg.target, 3) || !finiteVec(msg.goal, 3))
    return fail(why, "target or goal is not finite");
  if (msg.num_waypoints < 0 || msg.num_waypoints > kMaxWaypoints ||
      static_cast<size_t>(msg.num_waypoints) != msg.waypoints.size())
    return fail(why, "num_waypoints disagrees with the data");
  for (const auto& w : msg.waypoints) {
    if (w.size() != 3 || !finiteVec(w.data(), 3)) return fail(why, "bad waypoint");
  }
  if (msg.start_utime < 0 || msg.deadline_utime < 0) return fail(why, "negative time");
  if (msg.start_utime > kMaxUtime_us || msg.deadline_utime > kMaxUtime_us)
    return fail(why, "absurd time");
  if (!std::isfinite(msg.max_speed_mps) || msg.max_speed_mps < 0.0 || msg.max_speed_mps > 1e3)
    return fail(why, "max_speed_mps is not finite, negative or absurd");
  return validate(msg.reference, why);
}

bool validate(const plan_result_t& msg, std::string* why) {
  if (!validate(msg.header, why)) return false;
  if (msg.status != plan_result_t::STATUS_OK && msg.status != plan_result_t::STATUS_FAILED)
    return fail(why, "unknown status");
  // Answers come from a planning mode; the arbiter indexes its per-mode counters with it.
  if (msg.mode < plan_request_t::MODE_FPM || msg.mode > plan_request_t::MODE_EAM)
    return fail(why, "unknown mode " + std::to_string(msg.mode));
  if (msg.reason < 0) return fail(why, "negative reason code");
  if (msg.compute_us < 0) return fail(why, "negative compute time");
  if (msg.status == plan_result_t::STATUS_OK && msg.trajectory.num_pieces == 0)
    return fail(why, "successful result without a trajectory");
  const double costs[4] = {msg.cost_total, msg.cost_control, msg.cost_time, msg.cost_penalty};
  if (!finiteVec(costs, 4, 1e300)) return fail(why, "cost is not finite");
  if (!validText(msg.detail, kMaxTextLength)) return fail(why, "detail is too long or has a NUL");
  return validate(msg.trajectory, why);
}

bool validate(const arbiter_status_t& msg, std::string* why) {
  if (!validate(msg.header, why)) return false;
  if (!finiteVec(msg.position, 3) || !finiteVec(msg.local_target, 3))
    return fail(why, "non-finite coordinates");
  if (!validText(msg.detail, kMaxTextLength)) return fail(why, "detail is too long or has a NUL");
  if (!validText(msg.degraded_reason, kMaxTextLength))
    return fail(why, "degraded_reason is too long or has a NUL");
  if (!std::isfinite(msg.replan_lead_s) || !std::isfinite(msg.answer_deadline_s) ||
      msg.replan_lead_s < 0.0 || msg.answer_deadline_s < 0.0)
    return fail(why, "replan_lead_s or answer_deadline_s is negative or not finite");
  return true;
}

bool validate(const heartbeat_t& msg, std::string* why) {
  if (!validate(msg.header, why)) return false;
  if (msg.num_counters < 0 || msg.num_counters > kMaxHeartbeatCounters ||
      static_cast<size_t>(msg.num_counters) != msg.counter_names.size() ||
      msg.counter_names.size() != msg.counter_values.size())
    return fail(why, "num_counters disagrees with the data");
  if (!validIdentifier(msg.service) || !validIdentifier(msg.host))
    return fail(why, "service or host is too long or has control characters");
  if (!validText(msg.state_detail, kMaxTextLength))
    return fail(why, "state_detail is too long or has a NUL");
  for (const std::string& name : msg.counter_names) {
    if (!validIdentifier(name))
      return fail(why, "counter name is too long or has control characters");
  }
  return true;
}

bool validate(const mission_status_t& msg, std::string* why) {
  if (!validate(msg.header, why)) return false;
  const double v[3] = {msg.flight_time_s, msg.distance_m, msg.energy};
  if (!finiteVec(v, 3, 1e12)) return fail(why, "non-finite metrics");
  const double e[2] = {msg.tracking_error_rms_m, msg.tracking_error_max_m};
  if (!finiteVec(e, 2, 1e6)) return fail(why, "non-finite tracking error");
  if (msg.num_waypoints < 0 || msg.num_waypoints > kMaxWaypoints || msg.waypoint_index < 0)
    return fail(why, "waypoint_index or num_waypoints out of range");
  if (msg.num_arrivals < 0 || msg.num_arrivals > kMaxWaypoints ||
      static_cast<size_t>(msg.num_arrivals) != msg.arrival_waypoint.size() ||
      msg.arrival_waypoint.size() != msg.arrival_time_s.size() ||
      msg.arrival_waypoint.size() != msg.arrival_speed_mps.size())
    return fail(why, "num_arrivals disagrees with the data");
  for (size_t i = 0; i < msg.arrival_time_s.size(); ++i) {
    const double a[2] = {msg.arrival_time_s[i], msg.arrival_speed_mps[i]};
    if (!finiteVec(a, 2, 1e12)) return fail(why, "non-finite arrival");
  }
  return true;
}

bool validate(const setpoint_t& msg, std::string* why) {
  if (!validate(msg.header, why)) return false;
  if (msg.trajectory_id < 0) return fail(why, "trajectory_id is negative");
  if (msg.state < setpoint_t::STATE_HOLD || msg.state > setpoint_t::STATE_HOVER)
    return fail(why, "unknown state " + std::to_string(msg.state));
  if (!finiteVec(msg.position, 3)) return fail(why, "position is not finite");
  if (!finiteVec(msg.velocity, 3, 1e3) || !finiteVec(msg.acceleration, 3, 1e4) ||
      !finiteVec(msg.jerk, 3, 1e6))
    return fail(why, "velocity, acceleration or jerk is not finite or absurd");
  const double yaw[2] = {msg.yaw_rad, msg.yaw_rate_radps};
  if (!finiteVec(yaw, 2, 1e3)) return fail(why, "yaw or yaw rate is not finite");
  return true;
}

bool validate(const plan_debug_t& msg, std::string* why) {
  if (!validate(msg.header, why)) return false;
  if (msg.mode < plan_request_t::MODE_FPM || msg.mode > plan_request_t::MODE_EAM)
    return fail(why, "unknown mode " + std::to_string(msg.mode));
  if (!sized(msg.num_paths, msg.path_points) || !sized(msg.num_path_coords, msg.path_xyz) ||
      !sized(msg.num_polytopes, msg.polytope_faces) || !sized(msg.num_face_values, msg.faces) ||
      !sized(msg.num_control_coords, msg.control_xyz) ||
      !sized(msg.num_pairs, msg.pair_control_point) || !sized(msg.num_pair_coords, msg.pair_p) ||
      msg.pair_v.size() != msg.pair_p.size())
    return fail(why, "a count disagrees with its data");
  if (!partitions(msg.path_points, 3, msg.path_xyz.size()) ||
      !partitions(msg.polytope_faces, 4, msg.faces.size()) || msg.control_xyz.size() % 3 != 0 ||
      msg.pair_p.size() != 3 * msg.pair_control_point.size())
    return fail(why, "the per-path, per-polytope or per-pair counts disagree with the data");
  const int64_t control_points = static_cast<int64_t>(msg.control_xyz.size() / 3);
  for (int32_t q : msg.pair_control_point) {
    if (q < 0 || q >= control_points) return fail(why, "a pair names no control point");
  }
  if (!finiteFloats(msg.path_xyz) || !finiteFloats(msg.faces) || !finiteFloats(msg.control_xyz) ||
      !finiteFloats(msg.pair_p) || !finiteFloats(msg.pair_v))
    return fail(why, "non-finite or absurd coordinates");
  return true;
}

}  // namespace mmh
