#include "bad_messages.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <random>

#include "mmh/awareness_t.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/common/voxel_grid.hpp"
#include "mmh/goal_t.hpp"
#include "mmh/local_map_t.hpp"
#include "mmh/odometry_t.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/plan_result_t.hpp"
#include "mmh/pointcloud_t.hpp"
#include "mmh/trajectory_t.hpp"

namespace mmh::bad_input {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr const char* kSource = "mmh-bad-input";

const std::vector<std::string> kOdometryReceivers = {"mmh-mapping", "mmh-awareness", "mmh-arbiter"};
const std::vector<std::string> kMapReceivers = {"mmh-awareness", "mmh-som", "mmh-eam",
                                                "mmh-arbiter"};
const std::vector<std::string> kGoalReceivers = {"mmh-awareness", "mmh-arbiter"};

template <class Msg>
std::vector<uint8_t> encode(const Msg& msg) {
  std::vector<uint8_t> buf(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

void putInt32BigEndian(std::vector<uint8_t>& buf, size_t offset, int32_t value) {
  const auto v = static_cast<uint32_t>(value);
  for (int i = 0; i < 4; ++i) buf[offset + i] = static_cast<uint8_t>(v >> (24 - 8 * i));
}

// `full` encoded with the length field of its last array set to `length` (the data unchanged).
// `empty` is the same message with that array empty: its size less 4 is where the field starts.
template <class Msg>
std::vector<uint8_t> withLastArrayLength(const Msg& full, const Msg& empty, int32_t length) {
  std::vector<uint8_t> buf = encode(full);
  putInt32BigEndian(buf, static_cast<size_t>(empty.getEncodedSize()) - 4, length);
  return buf;
}

std::vector<Expectation> each(const std::vector<std::string>& services,
                              const std::string& counter) {
  std::vector<Expectation> out;
  for (const std::string& s : services) out.push_back({s, counter});
  return out;
}

// Stamps messages with a rising clock and per-channel sequence numbers, as a well-behaved
// publisher would, so that only the intended defect is wrong.
class Stamper {
 public:
  explicit Stamper(int64_t utime0) : utime_(utime0) {}
  header_t next(const std::string& channel) {
    header_t h;
    utime_ += 1000;
    h.utime = utime_;
    h.seq = ++seq_[channel];
    h.source = kSource;
    return h;
  }

 private:
  int64_t utime_;
  std::map<std::string, int64_t> seq_;
};

odometry_t odometry(header_t h) {
  odometry_t m{};
  m.header = std::move(h);
  m.position[2] = 1.2;
  m.orientation[0] = 1.0;
  return m;
}

pointcloud_t scan(header_t h, size_t points) {
  pointcloud_t m{};
  m.header = std::move(h);
  m.sensor_kind = pointcloud_t::SENSOR_DEPTH;
  m.sensor_position[2] = 1.2;
  m.sensor_orientation[0] = 1.0;
  m.max_range_m = 4.5f;
  m.xyz.resize(3 * points);
  for (size_t i = 0; i < points; ++i) {
    m.xyz[3 * i] = 2.0f + 0.001f * static_cast<float>(i % 1000);
    m.xyz[3 * i + 1] = 0.001f * static_cast<float>(i / 1000 % 1000);
    m.xyz[3 * i + 2] = 1.2f;
  }
  m.num_coords = static_cast<int32_t>(m.xyz.size());
  return m;
}

// A known 4 x 4 x 2 m window around the origin with a 0.6 m block of obstacle at (3, 0, 1.2).
local_map_t keyframeWithBlock(header_t h) {
  VoxelGrid g(0.1, Eigen::Vector3i(-20, -20, 0), Eigen::Vector3i(60, 40, 24));
  for (int64_t i = 0; i < g.numCells(); ++i) g.setLinear(i, Occupancy::kFree);
  for (double x = 2.75; x < 3.3; x += 0.1)
    for (double y = -0.25; y < 0.3; y += 0.1)
      for (double z = 0.95; z < 1.5; z += 0.1)
        g.set(g.localIndexOf(Eigen::Vector3d(x, y, z)), Occupancy::kOccupied);
  local_map_t m = makeKeyframe(g, 1);
  m.header = std::move(h);
  return m;
}

plan_request_t request(header_t h, int8_t mode) {
  plan_request_t m{};
  m.header = std::move(h);
  m.request_id = 900000 + m.header.seq;
  m.mode = mode;
  m.start_utime = m.header.utime + 50000;
  m.deadline_utime = m.header.utime + 40000;
  m.start_position[2] = 1.2;
  m.target[0] = 5.0;
  m.target[2] = 1.2;
  m.goal[0] = 5.0;
  m.goal[2] = 1.2;
  setWaypoints({}, m);
  return m;
}

trajectory_t straightTrajectory(header_t h) {
  Piece p;
  p.duration = 2.0;
  p.coeffs(0, 0) = 0.0;
  p.coeffs(2, 0) = 1.2;
  p.coeffs(0, 1) = 0.5;
  trajectory_t m{};
  m.header = std::move(h);
  m.trajectory_id = 900001;
  m.start_utime = m.header.utime;
  m.source_mode = plan_request_t::MODE_FPM;
  toMsg(Trajectory({p, p}), m);
  return m;
}

std::vector<uint8_t> garbage(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<uint8_t> out(n);
  for (auto& b : out) b = static_cast<uint8_t>(rng());
  return out;
}

void addStackMessages(std::vector<BadMessage>& out, Stamper& st, const CatalogueOptions& o) {
  const std::string odom = "ODOMETRY", cloud = "POINTCLOUD", goal = "GOAL", map = "LOCAL_MAP",
                    result = "PLAN_RESULT", aware = "AWARENESS";
  // --- ODOMETRY: mapping, awareness, arbiter -------------------------------------------------
  {
    odometry_t m = odometry(st.next(odom));
    m.position[0] = kNaN;
    out.push_back({"ODOMETRY with a NaN position", odom, encode(m),
                   each(kOdometryReceivers, "rejected_invalid")});
    m = odometry(st.next(odom));
    m.velocity[1] = kInf;
    out.push_back({"ODOMETRY with an infinite velocity", odom, encode(m),
                   each(kOdometryReceivers, "rejected_invalid")});
    m = odometry(st.next(odom));
    m.orientation[0] = 0.0;
    out.push_back({"ODOMETRY with a zero quaternion", odom, encode(m),
                   each(kOdometryReceivers, "rejected_invalid")});
    m = odometry(st.next(odom));
    std::vector<uint8_t> cut = encode(m);
    cut.resize(cut.size() - 9);
    out.push_back(
        {"ODOMETRY truncated by 9 bytes", odom, cut, each(kOdometryReceivers, "rejected_decode")});
    goal_t g{};
    g.header = st.next(odom);
    out.push_back({"a goal_t on ODOMETRY (wrong type)", odom, encode(g),
                   each(kOdometryReceivers, "rejected_decode")});
    out.push_back({"64 random bytes on ODOMETRY", odom, garbage(64, 1),
                   each(kOdometryReceivers, "rejected_decode")});
    // Time going backwards: one good message, then one 1 s older from the same publisher.
    const odometry_t good = odometry(st.next(odom));
    odometry_t back = odometry(st.next(odom));
    back.header.utime = good.header.utime - 1'000'000;
    out.push_back({"ODOMETRY (good, the reference for the next)", odom, encode(good), {}});
    out.push_back({"ODOMETRY 1 s older than the previous one", odom, encode(back),
                   each(kOdometryReceivers, "rejected_time_backwards")});
  }
  // --- POINTCLOUD: mapping ---------------------------------------------------------------------
  {
    pointcloud_t m = scan(st.next(cloud), 10);
    m.sensor_position[1] = kNaN;
    out.push_back({"POINTCLOUD with a NaN sensor position",
                   cloud,
                   encode(m),
                   {{"mmh-mapping", "rejected_invalid"}}});
    m = scan(st.next(cloud), 10);
    m.max_range_m = -1.f;
    out.push_back({"POINTCLOUD with a negative max range",
                   cloud,
                   encode(m),
                   {{"mmh-mapping", "rejected_invalid"}}});
    m = scan(st.next(cloud), 0);
    out.push_back({"POINTCLOUD with no point", cloud, encode(m), {{"mmh-mapping", "scan_empty"}}});
    m = scan(st.next(cloud), 100);
    for (float& v : m.xyz) v = std::numeric_limits<float>::quiet_NaN();
    out.push_back({"POINTCLOUD of NaN points only",
                   cloud,
                   encode(m),
                   {{"mmh-mapping", "scan_no_finite_point"}}});
    const pointcloud_t full = scan(st.next(cloud), 50);
    pointcloud_t empty = full;
    empty.xyz.clear();
    empty.num_coords = 0;
    out.push_back({"POINTCLOUD whose num_coords exceeds the data",
                   cloud,
                   withLastArrayLength(full, empty, full.num_coords + 300),
                   {{"mmh-mapping", "rejected_decode"}}});
    out.push_back({"POINTCLOUD with a negative num_coords",
                   cloud,
                   withLastArrayLength(full, empty, -6),
                   {{"mmh-mapping", "rejected_decode"}}});
    m = scan(st.next(cloud), 10);
    m.num_coords = 29;  // not a multiple of 3 (data agrees: 29 floats)
    m.xyz.resize(29);
    out.push_back({"POINTCLOUD with 29 coordinates",
                   cloud,
                   encode(m),
                   {{"mmh-mapping", "rejected_invalid"}}});
    if (o.huge_scan_points > 0) {
      m = scan(st.next(cloud), static_cast<size_t>(o.huge_scan_points));
      const char* counter =
          o.huge_scan_points > o.mapping_max_points ? "scan_too_large" : "scans_inserted";
      BadMessage huge{"POINTCLOUD of " + std::to_string(o.huge_scan_points) + " points",
                      cloud,
                      encode(m),
                      {{"mmh-mapping", counter}}};
      huge.pause_s = 1.0;
      out.push_back(std::move(huge));
    }
  }
  // --- GOAL: awareness, arbiter ----------------------------------------------------------------
  {
    goal_t g{};
    g.header = st.next(goal);
    g.goal_id = 901;
    g.position[0] = kNaN;
    out.push_back(
        {"GOAL with a NaN position", goal, encode(g), each(kGoalReceivers, "rejected_invalid")});
    g.header = st.next(goal);
    g.position[0] = 5.0;
    g.position[2] = 1.2;
    g.header.utime = int64_t{1} << 62;
    out.push_back({"GOAL stamped 146,000 years ahead", goal, encode(g),
                   each(kGoalReceivers, "rejected_invalid")});
    g.header = st.next(goal);
    g.header.utime += int64_t{3600} * 1'000'000;
    out.push_back({"GOAL stamped an hour ahead of the other messages", goal, encode(g),
                   each(kGoalReceivers, "rejected_time_jump")});
    g.header = st.next(goal);
    g.goal_id = -3;
    out.push_back(
        {"GOAL with a negative id", goal, encode(g), each(kGoalReceivers, "rejected_invalid")});
    g.header = st.next(goal);
    g.goal_id = 902;
    g.position[0] = 5000.0;
    out.push_back(
        {"GOAL outside the geofence", goal, encode(g), {{"mmh-arbiter", "rejected_goal"}}});
  }
  // --- LOCAL_MAP: awareness, som, eam, arbiter
  // ----------------------------------------------------
  {
    const local_map_t good = keyframeWithBlock(st.next(map));
    local_map_t m = good;
    m.header = st.next(map);
    m.resolution_m = kNaN;
    out.push_back({"LOCAL_MAP with a NaN resolution", map, encode(m),
                   each(kMapReceivers, "rejected_invalid")});
    m = good;
    m.header = st.next(map);
    m.size[0] = -40;
    out.push_back({"LOCAL_MAP with a negative size", map, encode(m),
                   each(kMapReceivers, "rejected_invalid")});
    m = good;
    m.header = st.next(map);
    m.size[0] = m.size[1] = m.size[2] = 100000;
    out.push_back(
        {"LOCAL_MAP of 10^15 cells", map, encode(m), each(kMapReceivers, "rejected_invalid")});
    m = good;
    m.header = st.next(map);
    local_map_t empty = m;
    empty.runs.clear();
    empty.num_bytes = 0;
    out.push_back({"LOCAL_MAP whose num_bytes exceeds the data", map,
                   withLastArrayLength(m, empty, m.num_bytes + 1000),
                   each(kMapReceivers, "rejected_decode")});
    out.push_back({"LOCAL_MAP with a negative num_bytes", map, withLastArrayLength(m, empty, -1),
                   each(kMapReceivers, "rejected_decode")});
    m = good;
    m.header = st.next(map);
    m.runs = {0x80, 0x80, 0x80, 0x80, 0x01, 0x05, 0x02};  // a run past the end of the window
    m.num_bytes = static_cast<int32_t>(m.runs.size());
    out.push_back({"LOCAL_MAP keyframe with a run outside the window", map, encode(m),
                   each(kMapReceivers, "msgs_rejected")});
    odometry_t o2 = odometry(st.next(map));
    out.push_back({"an odometry_t on LOCAL_MAP (wrong type)", map, encode(o2),
                   each(kMapReceivers, "rejected_decode")});
    // A good map with an obstacle, then a goal inside that obstacle: moved to the nearest free
    // point (arbiter.goal_relocate_radius_m), and counted.
    local_map_t fine = good;
    fine.header = st.next(map);
    out.push_back({"LOCAL_MAP (good, an obstacle at 3, 0, 1.2)", map, encode(fine), {}});
    goal_t g{};
    g.header = st.next(goal);
    g.goal_id = 903;
    g.position[0] = 3.0;
    g.position[2] = 1.2;
    BadMessage inside{"GOAL inside a mapped obstacle (moved out of it)",
                      goal,
                      encode(g),
                      {{"mmh-arbiter", "moved_goals"}}};
    inside.pause_s = 0.3;  // after the map above was applied
    out.push_back(std::move(inside));
  }
  // --- PLAN_REQUEST_*: fpm, som, eam -------------------------------------------------------
  {
    const std::pair<const char*, const char*> planners[] = {{"PLAN_REQUEST_FPM", "mmh-fpm"},
                                                            {"PLAN_REQUEST_SOM", "mmh-som"},
                                                            {"PLAN_REQUEST_EAM", "mmh-eam"}};
    const int8_t modes[] = {plan_request_t::MODE_FPM, plan_request_t::MODE_SOM,
                            plan_request_t::MODE_EAM};
    for (int i = 0; i < 3; ++i) {
      const std::string ch = planners[i].first, svc = planners[i].second;
      plan_request_t r = request(st.next(ch), modes[i]);
      r.start_velocity[0] = kNaN;
      out.push_back(
          {ch + " with a NaN start velocity", ch, encode(r), {{svc, "rejected_invalid"}}});
      r = request(st.next(ch), modes[i]);
      r.target[1] = -kInf;
      out.push_back({ch + " with an infinite target", ch, encode(r), {{svc, "rejected_invalid"}}});
      r = request(st.next(ch), modes[i]);
      r.max_speed_mps = -kInf;
      out.push_back({ch + " with an infinite negative speed limit",
                     ch,
                     encode(r),
                     {{svc, "rejected_invalid"}}});
      r = request(st.next(ch), modes[i]);
      r.mode = 42;
      out.push_back({ch + " with mode 42", ch, encode(r), {{svc, "rejected_invalid"}}});
      r = request(st.next(ch), modes[i]);
      r.reference = straightTrajectory(st.next(ch));
      r.reference.pieces[1].duration_s = -1.0;
      out.push_back({ch + " with a negative reference piece duration",
                     ch,
                     encode(r),
                     {{svc, "rejected_invalid"}}});
      r = request(st.next(ch), modes[i]);
      std::vector<uint8_t> cut = encode(r);
      cut.resize(cut.size() / 2);
      out.push_back({ch + " cut in half", ch, cut, {{svc, "rejected_decode"}}});
      goal_t g{};
      g.header = st.next(ch);
      out.push_back(
          {"a goal_t on " + ch + " (wrong type)", ch, encode(g), {{svc, "rejected_decode"}}});
      r = request(st.next(ch), modes[i]);
      r.target[0] = 500.0;  // finite, but far outside the geofence
      out.push_back(
          {ch + " with a target outside the geofence", ch, encode(r), {{svc, "failed_reason_5"}}});
    }
  }
  // --- PLAN_RESULT and AWARENESS: arbiter ------------------------------------------------------
  {
    plan_result_t r{};
    r.header = st.next(result);
    r.request_id = 1;
    r.mode = 99;
    r.status = plan_result_t::STATUS_FAILED;
    out.push_back(
        {"PLAN_RESULT of mode 99", result, encode(r), {{"mmh-arbiter", "rejected_invalid"}}});
    r.header = st.next(result);
    r.mode = plan_request_t::MODE_SOM;
    r.cost_total = kNaN;
    out.push_back(
        {"PLAN_RESULT with a NaN cost", result, encode(r), {{"mmh-arbiter", "rejected_invalid"}}});
    r.header = st.next(result);
    r.cost_total = 0.0;
    r.status = plan_result_t::STATUS_OK;
    r.trajectory = straightTrajectory(st.next(result));
    r.trajectory.pieces[0].duration_s = r.trajectory.pieces[1].duration_s = 9000.0;
    out.push_back({"PLAN_RESULT with a trajectory lasting 5 hours",
                   result,
                   encode(r),
                   {{"mmh-arbiter", "rejected_invalid"}}});
    r.header = st.next(result);
    r.trajectory = trajectory_t{};  // OK without a trajectory
    out.push_back({"PLAN_RESULT OK without a trajectory",
                   result,
                   encode(r),
                   {{"mmh-arbiter", "rejected_invalid"}}});
    awareness_t a{};
    a.header = st.next(aware);
    a.reason = 7;
    out.push_back(
        {"AWARENESS with reason 7", aware, encode(a), {{"mmh-arbiter", "rejected_invalid"}}});
    a.header = st.next(aware);
    a.reason = awareness_t::REASON_CLEAR;
    a.ray_end[2] = kInf;
    out.push_back({"AWARENESS with an infinite ray end",
                   aware,
                   encode(a),
                   {{"mmh-arbiter", "rejected_invalid"}}});
    out.push_back({"200 random bytes on AWARENESS",
                   aware,
                   garbage(200, 2),
                   {{"mmh-arbiter", "rejected_decode"}}});
  }
}

void addSimMessages(std::vector<BadMessage>& out, Stamper& st) {
  const std::string traj = "TRAJECTORY", goal = "GOAL";
  trajectory_t t = straightTrajectory(st.next(traj));
  t.pieces[0].coeffs[1][3] = kNaN;
  out.push_back(
      {"TRAJECTORY with a NaN coefficient", traj, encode(t), {{"mmh-sim", "rejected_invalid"}}});
  t = straightTrajectory(st.next(traj));
  t.pieces[1].duration_s = 0.0;
  out.push_back({"TRAJECTORY with a zero piece duration",
                 traj,
                 encode(t),
                 {{"mmh-sim", "rejected_invalid"}}});
  t = straightTrajectory(st.next(traj));
  t.source_mode = 17;
  out.push_back({"TRAJECTORY from mode 17", traj, encode(t), {{"mmh-sim", "rejected_invalid"}}});
  t = straightTrajectory(st.next(traj));
  t.pieces[0].duration_s = t.pieces[1].duration_s = 9000.0;
  out.push_back({"TRAJECTORY lasting 5 hours", traj, encode(t), {{"mmh-sim", "rejected_invalid"}}});
  t = straightTrajectory(st.next(traj));
  trajectory_t empty = t;
  empty.pieces.clear();
  empty.num_pieces = 0;
  out.push_back({"TRAJECTORY whose num_pieces exceeds the data",
                 traj,
                 withLastArrayLength(t, empty, 7),
                 {{"mmh-sim", "rejected_decode"}}});
  out.push_back({"TRAJECTORY with a negative num_pieces",
                 traj,
                 withLastArrayLength(t, empty, -2),
                 {{"mmh-sim", "rejected_decode"}}});
  odometry_t o = odometry(st.next(traj));
  out.push_back({"an odometry_t on TRAJECTORY (wrong type)",
                 traj,
                 encode(o),
                 {{"mmh-sim", "rejected_decode"}}});
  goal_t g{};
  g.header = st.next(goal);
  g.goal_id = 1;
  g.position[1] = kNaN;
  out.push_back({"GOAL with a NaN position", goal, encode(g), {{"mmh-sim", "rejected_invalid"}}});
}

}  // namespace

std::vector<std::string> servicesOf(Target target) {
  if (target == Target::kSim) return {"mmh-sim"};
  return {"mmh-mapping", "mmh-awareness", "mmh-fpm", "mmh-som", "mmh-eam", "mmh-arbiter"};
}

std::vector<BadMessage> makeBadMessages(Target target, const CatalogueOptions& options) {
  std::vector<BadMessage> out;
  Stamper stamper(options.utime0);
  if (target == Target::kSim)
    addSimMessages(out, stamper);
  else
    addStackMessages(out, stamper, options);
  return out;
}

}  // namespace mmh::bad_input
