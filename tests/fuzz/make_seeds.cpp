// Writes the seed corpus of the fuzz targets: one or two valid encoded messages of every type (and
// an invalid one for odometry), as tests/fuzz/corpus/<type>/<name>. Run by hand when a type
// changes:
//   build-fuzz/bin/mmh-fuzz-seeds tests/fuzz/corpus
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "mmh/arbiter_status_t.hpp"
#include "mmh/awareness_t.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/common/voxel_grid.hpp"
#include "mmh/goal_t.hpp"
#include "mmh/heartbeat_t.hpp"
#include "mmh/mission_status_t.hpp"
#include "mmh/odometry_t.hpp"
#include "mmh/plan_debug_t.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/plan_result_t.hpp"
#include "mmh/pointcloud_t.hpp"
#include "mmh/setpoint_t.hpp"

namespace fs = std::filesystem;
using namespace mmh;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
fs::path g_root;

template <class Msg>
void write(const Msg& msg, const std::string& name) {
  const fs::path dir = g_root / Msg::getTypeName();
  fs::create_directories(dir);
  std::vector<uint8_t> buf(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
  std::ofstream(dir / name, std::ios::binary)
      .write(reinterpret_cast<const char*>(buf.data()), static_cast<std::streamsize>(buf.size()));
}

header_t header(int64_t utime, const std::string& source) {
  header_t h;
  h.utime = utime;
  h.seq = 1;
  h.source = source;
  return h;
}

Trajectory sampleTrajectory(int pieces) {
  std::vector<Piece> out;
  for (int i = 0; i < pieces; ++i) {
    Piece p;
    p.duration = 0.8 + 0.1 * i;
    p.coeffs(0, 0) = i;
    p.coeffs(0, 1) = 1.0;
    p.coeffs(1, 2) = 0.2;
    p.coeffs(2, 0) = 1.2;
    p.coeffs(2, 3) = -0.01;
    out.push_back(p);
  }
  return Trajectory(out);
}

trajectory_t trajectoryMsg(int pieces) {
  trajectory_t t{};
  t.header = header(2'000'000, "mmh-arbiter");
  t.trajectory_id = 4;
  t.start_utime = 2'000'000;
  t.source_mode = plan_request_t::MODE_SOM;
  toMsg(sampleTrajectory(pieces), t);
  return t;
}

void odometry() {
  odometry_t m{};
  m.header = header(1'000'000, "mmh-sim");
  m.position[2] = 1.2;
  m.velocity[0] = 2.0;
  m.orientation[0] = 1.0;
  write(m, "hover");
  m.velocity[1] = kNaN;
  write(m, "nan-velocity");
}

void pointcloud() {
  pointcloud_t m{};
  m.header = header(1'000'000, "mmh-sim");
  m.sensor_kind = pointcloud_t::SENSOR_DEPTH;
  m.sensor_position[2] = 1.2;
  m.sensor_orientation[0] = 1.0;
  m.max_range_m = 4.5f;
  for (int i = 0; i < 8; ++i) {
    m.xyz.insert(m.xyz.end(), {1.0f + 0.1f * i, 0.2f * i, 1.0f});
  }
  m.num_coords = static_cast<int32_t>(m.xyz.size());
  write(m, "depth-8-points");
  m.sensor_kind = pointcloud_t::SENSOR_LIDAR;
  m.xyz.clear();
  m.num_coords = 0;
  write(m, "lidar-empty");
}

void goal() {
  goal_t m{};
  m.header = header(1'000'000, "mmh-goal");
  m.goal_id = 1;
  m.position[0] = 19.95;
  m.position[2] = 1.2;
  write(m, "mission");
  m.goal_id = 3;
  m.waypoint_index = 1;
  m.num_waypoints = 3;
  m.tolerance_m = 1.0;
  write(m, "waypoint");
}

void localMap() {
  VoxelGrid grid(0.1, Eigen::Vector3i(-8, -8, 0), Eigen::Vector3i(16, 16, 4));
  for (int x = 3; x < 6; ++x) grid.set(Eigen::Vector3i(x, 7, 1), Occupancy::kOccupied);
  for (int x = 0; x < 16; ++x) grid.set(Eigen::Vector3i(x, 2, 0), Occupancy::kFree);
  local_map_t key = makeKeyframe(grid, 5);
  key.header = header(1'000'000, "mmh-mapping");
  write(key, "keyframe");
  grid.shiftTo(Eigen::Vector3i(-7, -8, 0));
  local_map_t delta =
      makeDelta(grid, 6,
                {{grid.linearIndex(Eigen::Vector3i(1, 1, 1)), Occupancy::kOccupied},
                 {grid.linearIndex(Eigen::Vector3i(2, 1, 1)), Occupancy::kOccupied}});
  delta.header = header(1'066'000, "mmh-mapping");
  write(delta, "delta");
}

void awareness() {
  awareness_t m{};
  m.header = header(1'000'000, "mmh-awareness");
  m.safe = false;
  m.reason = awareness_t::REASON_NARROW;
  m.map_seq = 5;
  m.goal_id = 1;
  m.goal[0] = 19.95;
  m.ray_end[0] = 4.5;
  m.has_blocked_point = true;
  m.first_blocked[0] = 2.0;
  write(m, "narrow");
}

void trajectory() {
  write(trajectoryMsg(3), "three-pieces");
  trajectory_t empty{};
  empty.header = header(2'000'000, "mmh-arbiter");
  empty.start_utime = 2'000'000;
  write(empty, "hold");
}

void planRequest() {
  plan_request_t m{};
  m.header = header(2'000'000, "mmh-arbiter");
  m.request_id = 9;
  m.mode = plan_request_t::MODE_FPM;
  m.start_utime = 2'100'000;
  setStartState(sampleTrajectory(1).state(0.0), m);
  m.target[0] = 10.0;
  m.goal[0] = 19.95;
  m.deadline_utime = 2'200'000;
  m.max_speed_mps = 2.4;
  m.map_seq = 5;
  setWaypoints({Eigen::Vector3d(3, 1, 1.2), Eigen::Vector3d(6, -1, 1.2)}, m);
  write(m, "fpm-waypoints");
  m.mode = plan_request_t::MODE_EAM;
  setWaypoints({}, m);
  m.reference = trajectoryMsg(2);
  write(m, "eam-reference");
}

void planResult() {
  plan_result_t m{};
  m.header = header(2'050'000, "mmh-som");
  m.request_id = 9;
  m.mode = plan_request_t::MODE_SOM;
  m.status = plan_result_t::STATUS_OK;
  m.detail = "ok";
  m.compute_us = 1400;
  m.map_seq = 5;
  m.cost_total = 3.0;
  m.trajectory = trajectoryMsg(4);
  write(m, "ok");
  m.status = plan_result_t::STATUS_FAILED;
  m.reason = plan_result_t::REASON_NO_PATH;
  m.detail = "no path";
  m.trajectory = trajectory_t{};
  write(m, "failed");
}

void arbiterStatus() {
  arbiter_status_t m{};
  m.header = header(2'000'000, "mmh-arbiter");
  m.decision_seq = 3;
  m.trigger = arbiter_status_t::TRIGGER_HALFWAY;
  m.outcome = arbiter_status_t::OUTCOME_COMMITTED;
  m.committed_mode = plan_request_t::MODE_SOM;
  m.modes_asked = 1 << plan_request_t::MODE_SOM;
  m.position[2] = 1.2;
  m.detail = "committed SOM";
  m.replan_lead_s = 0.05;
  m.answer_deadline_s = 0.04;
  write(m, "committed");
  m.replan_lead_s = 0.19;
  m.answer_deadline_s = 0.18;
  m.degraded = true;
  m.degraded_reason = "answers late (p99 120 ms): deadline 180 ms, lead 190 ms";
  write(m, "degraded");
}

void planDebug() {
  plan_debug_t m{};
  m.header = header(2'000'000, "mmh-som");
  m.request_id = 7;
  m.mode = plan_request_t::MODE_SOM;
  m.ok = true;
  m.path_points = {2};
  m.num_paths = 1;
  m.path_xyz = {0, 0, 1.2f, 2, 0, 1.2f};
  m.num_path_coords = 6;
  m.polytope_faces = {1};
  m.num_polytopes = 1;
  m.faces = {1, 0, 0, 3};
  m.num_face_values = 4;
  write(m, "som");
  plan_debug_t e{};
  e.header = header(2'000'000, "mmh-eam");
  e.request_id = 8;
  e.mode = plan_request_t::MODE_EAM;
  e.control_xyz = {0, 0, 1.2f, 1, 0, 1.2f};
  e.num_control_coords = 6;
  e.pair_control_point = {1};
  e.num_pairs = 1;
  e.pair_p = {1, 0.3f, 1.2f};
  e.pair_v = {0, 1, 0};
  e.num_pair_coords = 3;
  write(e, "eam");
}

void heartbeat() {
  heartbeat_t m{};
  m.header = header(1'000'000, "mmh-mapping");
  m.service = "mmh-mapping";
  m.host = "vm";
  m.pid = 42;
  m.state = heartbeat_t::STATE_OK;
  m.state_detail = "";
  m.counter_names = {"rejected_decode", "map_gaps"};
  m.counter_values = {1, 0};
  m.num_counters = 2;
  write(m, "counters");
}

void missionStatus() {
  mission_status_t m{};
  m.header = header(9'000'000, "mmh-sim");
  m.reached = true;
  m.flight_time_s = 16.7;
  m.distance_m = 40.0;
  m.energy = 241.3;
  write(m, "reached");
  m.num_waypoints = 2;
  m.waypoint_index = 1;
  m.num_arrivals = 2;
  m.arrival_waypoint = {0, 1};
  m.arrival_time_s = {8.1, 16.7};
  m.arrival_speed_mps = {2.4, 0.1};
  m.follows_setpoints = true;
  m.tracking_error_rms_m = 0.04;
  m.tracking_error_max_m = 0.12;
  write(m, "mission-tracked");
}

void setpoint() {
  setpoint_t m{};
  m.header = header(2'000'000, "mmh-setpoint");
  m.trajectory_id = 4;
  m.state = setpoint_t::STATE_TRACKING;
  m.position[0] = 1.0;
  m.position[2] = 1.2;
  m.velocity[0] = 2.5;
  m.acceleration[1] = -0.4;
  m.jerk[2] = 0.1;
  m.yaw_rad = 0.3;
  m.yaw_rate_radps = 0.05;
  write(m, "tracking");
  m.state = setpoint_t::STATE_HOVER;
  write(m, "hover");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: mmh-fuzz-seeds CORPUS_DIR\n");
    return 1;
  }
  g_root = argv[1];
  odometry();
  pointcloud();
  goal();
  setpoint();
  localMap();
  awareness();
  trajectory();
  planRequest();
  planResult();
  arbiterStatus();
  planDebug();
  heartbeat();
  missionStatus();
  return 0;
}
