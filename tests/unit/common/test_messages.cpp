// Encode/decode round trips of every LCM type and the validators' verdicts on bad fields.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/message_validation.hpp"
#include "mmh/common/msg_convert.hpp"

namespace {

template <class Msg>
Msg roundTrip(const Msg& in) {
  std::vector<uint8_t> buf(in.getEncodedSize());
  EXPECT_EQ(in.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  Msg out;
  EXPECT_EQ(out.decode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  return out;
}

mmh::header_t header(int64_t utime) {
  mmh::header_t h;
  h.utime = utime;
  h.seq = 3;
  h.source = "test";
  return h;
}

mmh::trajectory_t sampleTrajectory() {
  mmh::Piece p;
  p.duration = 1.5;
  p.coeffs(0, 1) = 2.0;
  p.coeffs(2, 5) = -0.25;
  mmh::trajectory_t t{};
  t.header = header(10);
  t.trajectory_id = 7;
  t.start_utime = 100;
  t.source_mode = mmh::plan_request_t::MODE_SOM;
  mmh::toMsg(mmh::Trajectory({p, p}), t);
  return t;
}

}  // namespace

TEST(Messages, OdometryRoundTripAndValidation) {
  mmh::odometry_t m{};
  m.header = header(1234);
  m.position[0] = 1.5;
  m.velocity[1] = -2.0;
  m.orientation[0] = 1.0;
  auto back = roundTrip(m);
  EXPECT_EQ(back.header.utime, 1234);
  EXPECT_EQ(back.header.source, "test");
  EXPECT_DOUBLE_EQ(back.velocity[1], -2.0);
  std::string why;
  EXPECT_TRUE(mmh::validate(back, &why)) << why;
  back.position[2] = std::nan("");
  EXPECT_FALSE(mmh::validate(back, &why));
  EXPECT_NE(why.find("position"), std::string::npos);
  back.position[2] = 0;
  back.orientation[0] = 0;  // zero quaternion
  EXPECT_FALSE(mmh::validate(back, &why));
  back.orientation[0] = 1;
  back.velocity[0] = INFINITY;
  EXPECT_FALSE(mmh::validate(back, &why));
}

TEST(Messages, PointcloudRoundTripAndValidation) {
  mmh::pointcloud_t m{};
  m.header = header(5);
  m.sensor_kind = mmh::pointcloud_t::SENSOR_DEPTH;
  m.sensor_orientation[0] = 1.0;
  m.max_range_m = 4.5f;
  m.xyz = {1.f, 2.f, 3.f, 4.f, 5.f, 6.f};
  m.num_coords = 6;
  auto back = roundTrip(m);
  EXPECT_EQ(back.xyz, m.xyz);
  std::string why;
  EXPECT_TRUE(mmh::validate(back, &why)) << why;
  back.num_coords = 5;
  EXPECT_FALSE(mmh::validate(back, &why));
  back.num_coords = 6;
  back.sensor_position[1] = NAN;
  EXPECT_FALSE(mmh::validate(back, &why));
  back.sensor_position[1] = 0;
  back.sensor_kind = 9;
  EXPECT_FALSE(mmh::validate(back, &why));
  // NaN points are the mapping service's business (it drops and counts them), not a rejection.
  back.sensor_kind = mmh::pointcloud_t::SENSOR_LIDAR;
  back.xyz[0] = NAN;
  EXPECT_TRUE(mmh::validate(back, &why));
}

TEST(Messages, GoalAwarenessStatusHeartbeatMission) {
  mmh::goal_t g{};
  g.header = header(1);
  g.goal_id = 2;
  g.position[0] = 19.9;
  EXPECT_DOUBLE_EQ(roundTrip(g).position[0], 19.9);
  std::string why;
  EXPECT_TRUE(mmh::validate(g, &why));
  g.position[1] = INFINITY;
  EXPECT_FALSE(mmh::validate(g, &why));

  mmh::awareness_t a{};
  a.header = header(2);
  a.safe = false;
  a.reason = mmh::awareness_t::REASON_NARROW;
  EXPECT_EQ(roundTrip(a).reason, mmh::awareness_t::REASON_NARROW);
  EXPECT_TRUE(mmh::validate(a, &why));
  a.reason = 7;
  EXPECT_FALSE(mmh::validate(a, &why));

  mmh::arbiter_status_t s{};
  s.header = header(3);
  s.detail = "halfway";
  s.iterations_som = 4;
  EXPECT_EQ(roundTrip(s).iterations_som, 4);
  EXPECT_TRUE(mmh::validate(s, &why));
  s.degraded_reason = std::string("late\0", 5);  // a NUL would not survive re-encoding
  EXPECT_FALSE(mmh::validate(s, &why));
  s.degraded_reason = "answers late";
  s.answer_deadline_s = NAN;
  EXPECT_FALSE(mmh::validate(s, &why));

  mmh::heartbeat_t h{};
  h.header = header(4);
  h.service = "mmh-som";
  h.counter_names = {"rejected_nan"};
  h.counter_values = {3};
  h.num_counters = 1;
  EXPECT_EQ(roundTrip(h).counter_values[0], 3);
  EXPECT_TRUE(mmh::validate(h, &why));
  h.counter_values.push_back(1);
  EXPECT_FALSE(mmh::validate(h, &why));

  mmh::mission_status_t ms{};
  ms.header = header(5);
  ms.reached = true;
  ms.energy = 15.5;
  EXPECT_TRUE(roundTrip(ms).reached);
  EXPECT_TRUE(mmh::validate(ms, &why));
  ms.energy = NAN;
  EXPECT_FALSE(mmh::validate(ms, &why));
}

TEST(Messages, TrajectoryRequestResultRoundTrip) {
  mmh::trajectory_t t = sampleTrajectory();
  auto tb = roundTrip(t);
  EXPECT_EQ(tb.num_pieces, 2);
  EXPECT_DOUBLE_EQ(tb.pieces[1].coeffs[2][5], -0.25);
  std::string why;
  EXPECT_TRUE(mmh::validate(tb, &why)) << why;
  tb.pieces[0].duration_s = 0.0;
  EXPECT_FALSE(mmh::validate(tb, &why));
  tb.pieces[0].duration_s = 1.0;
  tb.num_pieces = 3;
  EXPECT_FALSE(mmh::validate(tb, &why));

  mmh::plan_request_t r{};
  r.header = header(6);
  r.request_id = 11;
  r.mode = mmh::plan_request_t::MODE_EAM;
  r.target[0] = 15.0;
  mmh::setWaypoints({Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(4, 5, 6)}, r);
  r.reference = t;
  auto rb = roundTrip(r);
  ASSERT_EQ(mmh::getWaypoints(rb).size(), 2u);
  EXPECT_TRUE(mmh::getWaypoints(rb)[1].isApprox(Eigen::Vector3d(4, 5, 6)));
  EXPECT_EQ(rb.reference.num_pieces, 2);
  EXPECT_TRUE(mmh::validate(rb, &why)) << why;
  rb.start_velocity[0] = NAN;
  EXPECT_FALSE(mmh::validate(rb, &why));
  rb.start_velocity[0] = 0;
  rb.mode = 0;
  EXPECT_FALSE(mmh::validate(rb, &why));
  rb.mode = mmh::plan_request_t::MODE_FPM;
  rb.waypoints[0].resize(2);  // inner array too short: must not reach the encoder
  EXPECT_FALSE(mmh::validate(rb, &why));

  mmh::plan_result_t res{};
  res.header = header(7);
  res.request_id = 11;
  res.mode = mmh::plan_request_t::MODE_SOM;
  res.status = mmh::plan_result_t::STATUS_OK;
  res.trajectory = t;
  res.compute_us = 250;
  EXPECT_EQ(roundTrip(res).trajectory.num_pieces, 2);
  EXPECT_TRUE(mmh::validate(res, &why)) << why;
  res.trajectory = mmh::trajectory_t{};
  EXPECT_FALSE(mmh::validate(res, &why));  // OK without a trajectory
  res.status = mmh::plan_result_t::STATUS_FAILED;
  res.reason = mmh::plan_result_t::REASON_NO_PATH;
  EXPECT_TRUE(mmh::validate(res, &why)) << why;
}

TEST(Messages, LocalMapRoundTrip) {
  mmh::VoxelGrid g(0.1, Eigen::Vector3i(1, 2, 3), Eigen::Vector3i(10, 10, 10));
  g.set(Eigen::Vector3i(1, 1, 1), mmh::Occupancy::kOccupied);
  mmh::local_map_t m = mmh::makeKeyframe(g, 1);
  m.header = header(8);
  auto back = roundTrip(m);
  EXPECT_EQ(back.runs, m.runs);
  std::string why;
  EXPECT_TRUE(mmh::validate(back, &why)) << why;
  back.map_seq = 0;
  EXPECT_FALSE(mmh::validate(back, &why));
}

TEST(Messages, TruncatedAndNegativeLengthBuffersFailToDecode) {
  mmh::pointcloud_t m{};
  m.header = header(5);
  m.sensor_orientation[0] = 1.0;
  m.xyz = std::vector<float>(30, 1.f);
  m.num_coords = 30;
  std::vector<uint8_t> buf(m.getEncodedSize());
  m.encode(buf.data(), 0, static_cast<int>(buf.size()));
  mmh::pointcloud_t out;
  EXPECT_LT(out.decode(buf.data(), 0, static_cast<int>(buf.size()) - 7), 0);
}

TEST(Messages, ValidatorsRefuseAbsurdTimesModesAndIds) {
  std::string why;
  mmh::goal_t g{};
  g.header = header(5);
  g.goal_id = 1;
  EXPECT_TRUE(mmh::validate(g, &why)) << why;
  g.goal_id = -1;
  EXPECT_FALSE(mmh::validate(g, &why));
  EXPECT_NE(why.find("goal_id"), std::string::npos);
  g.goal_id = 1;
  g.header.utime = int64_t{1} << 62;  // would drag every receiver's clock 146,000 years ahead
  EXPECT_FALSE(mmh::validate(g, &why));
  EXPECT_NE(why.find("utime"), std::string::npos);
  g.header.utime = mmh::kMaxUtime_us;
  EXPECT_TRUE(mmh::validate(g, &why)) << why;

  mmh::plan_result_t res{};
  res.header = header(7);
  res.mode = mmh::plan_request_t::MODE_EAM;
  res.status = mmh::plan_result_t::STATUS_FAILED;
  EXPECT_TRUE(mmh::validate(res, &why)) << why;
  for (int8_t mode : {int8_t{0}, int8_t{mmh::plan_request_t::MODE_STOP}, int8_t{99}, int8_t{-1}}) {
    res.mode = mode;
    EXPECT_FALSE(mmh::validate(res, &why)) << int(mode);  // the arbiter indexes by mode
  }
  res.mode = mmh::plan_request_t::MODE_EAM;
  res.reason = -4;
  EXPECT_FALSE(mmh::validate(res, &why));

  mmh::trajectory_t t = sampleTrajectory();
  t.source_mode = 17;
  EXPECT_FALSE(mmh::validate(t, &why));
  t.source_mode = mmh::plan_request_t::MODE_STOP;
  EXPECT_TRUE(mmh::validate(t, &why)) << why;
  t.start_utime = int64_t{1} << 62;
  EXPECT_FALSE(mmh::validate(t, &why));
  t = sampleTrajectory();
  t.pieces[0].duration_s = t.pieces[1].duration_s = 1900.0;  // each piece fine, 63 min in all
  EXPECT_FALSE(mmh::validate(t, &why));
  EXPECT_NE(why.find("hour"), std::string::npos);

  mmh::plan_request_t r{};
  r.header = header(6);
  r.mode = mmh::plan_request_t::MODE_FPM;
  EXPECT_TRUE(mmh::validate(r, &why)) << why;
  r.deadline_utime = int64_t{1} << 62;
  EXPECT_FALSE(mmh::validate(r, &why));
  r.deadline_utime = 0;
  r.max_speed_mps = 2.4;  // the arbiter's lowered limit
  EXPECT_TRUE(mmh::validate(r, &why)) << why;
  for (double bad : {-1.0, double(NAN), double(INFINITY)}) {
    r.max_speed_mps = bad;
    EXPECT_FALSE(mmh::validate(r, &why)) << bad;
    EXPECT_NE(why.find("max_speed_mps"), std::string::npos);
  }

  mmh::VoxelGrid grid(0.1, Eigen::Vector3i(0, 0, 0), Eigen::Vector3i(4, 4, 4));
  mmh::local_map_t m = mmh::makeKeyframe(grid, 1);
  m.header = header(8);
  EXPECT_TRUE(mmh::validate(m, &why)) << why;
  m.num_changed = -1;
  EXPECT_FALSE(mmh::validate(m, &why));
}

TEST(Messages, PlanDebugRoundTripAndValidation) {
  mmh::PlanDebug debug;
  debug.paths = {{Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 1)}, {Eigen::Vector3d(2, 0, 1)}};
  Eigen::Matrix<double, Eigen::Dynamic, 4> box(6, 4);
  box << 1, 0, 0, 1, -1, 0, 0, 0, 0, 1, 0, 1, 0, -1, 0, 0, 0, 0, 1, 1, 0, 0, -1, 0;
  debug.polytopes = {box, box};
  debug.control_points = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.5, 0, 0)};
  debug.pairs = {{1, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)}};
  mmh::plan_debug_t good = mmh::toDebugMsg(debug, 12, mmh::plan_request_t::MODE_EAM, true);
  good.header = header(50);
  EXPECT_EQ(good.num_paths, 2);
  EXPECT_EQ(good.path_points, (std::vector<int32_t>{2, 1}));
  EXPECT_EQ(good.num_path_coords, 9);
  EXPECT_EQ(good.num_polytopes, 2);
  EXPECT_EQ(good.num_face_values, 48);
  EXPECT_EQ(good.num_control_coords, 6);
  EXPECT_EQ(good.num_pairs, 1);
  EXPECT_EQ(good.pair_control_point, std::vector<int32_t>{1});
  std::string why;
  EXPECT_TRUE(mmh::validate(good, &why)) << why;
  const mmh::plan_debug_t back = roundTrip(good);
  EXPECT_TRUE(mmh::validate(back, &why)) << why;
  EXPECT_EQ(back.faces, good.faces);
  EXPECT_EQ(back.request_id, 12);

  mmh::plan_debug_t bad = good;
  bad.path_points[0] = 3;  // more points than coordinates
  EXPECT_FALSE(mmh::validate(bad, &why));
  bad = good;
  bad.polytope_faces[1] = 5;
  EXPECT_FALSE(mmh::validate(bad, &why));
  bad = good;
  bad.pair_control_point[0] = 2;  // no such control point
  EXPECT_FALSE(mmh::validate(bad, &why));
  bad = good;
  bad.faces[2] = std::nanf("");
  EXPECT_FALSE(mmh::validate(bad, &why));
  bad = good;
  bad.num_pairs = 2;
  EXPECT_FALSE(mmh::validate(bad, &why));
  bad = good;
  bad.pair_v.pop_back();
  bad.pair_v.pop_back();
  bad.pair_v.pop_back();
  EXPECT_FALSE(mmh::validate(bad, &why));
  bad = good;
  bad.mode = 9;
  EXPECT_FALSE(mmh::validate(bad, &why));
}
