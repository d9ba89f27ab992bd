// EamNode over memq:// (in-process LCM): LOCAL_MAP and PLAN_REQUEST_EAM in, PLAN_RESULT out.
#include <gtest/gtest.h>

#include "eam_node.hpp"
#include "eam_test_grids.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/msg_convert.hpp"

using Eigen::Vector3d;

namespace {

struct ResultSink {
  void onResult(const mmh::plan_result_t& m) { results.push_back(m); }
  std::vector<mmh::plan_result_t> results;
};

void drain(lcm::LCM& lcm) {
  while (lcm.handleTimeout(0) > 0) {
  }
}

mmh::Config config() {
  return mmh::Config::loadFile(std::string(MMH_SOURCE_DIR) + "/deploy/config/default.yaml");
}

// Request at t = 2 s, starting at the committed trajectory's state 0.5 s after it began.
mmh::plan_request_t makeRequest(int64_t id, const mmh::Trajectory& committed,
                                const Vector3d& target) {
  mmh::plan_request_t req{};
  req.header.utime = 2'000'000 + id;
  req.request_id = id;
  req.mode = mmh::plan_request_t::MODE_EAM;
  req.start_utime = 2'000'000;
  mmh::setStartState(committed.state(0.5), req);
  mmh::fromVec3(target, req.target);
  mmh::fromVec3(target, req.goal);
  req.deadline_utime = 3'000'000;
  req.map_seq = 1;
  req.reference.start_utime = 1'500'000;
  req.reference.source_mode = mmh::plan_request_t::MODE_FPM;
  req.reference.trajectory_id = 7;
  mmh::toMsg(committed, req.reference);
  return req;
}

}  // namespace

TEST(EamNode, AnswersEveryRequestWithAVerifiedResult) {
  auto lcm = mmh::openLcm("memq://");
  mmh::ServiceContext node_ctx(*lcm, "mmh-eam", "T_");
  mmh::ServiceContext test_ctx(*lcm, "test", "T_");
  mmh::EamNode node(node_ctx, config());
  ResultSink sink;
  test_ctx.subscribe(mmh::channels::kPlanResult, &ResultSink::onResult, &sink);

  const Vector3d start(0, 0, 1.2), target(10, 0, 1.2);
  const mmh::Trajectory committed = eam_test::straightLine(start, target, 7.0);

  // No map yet: a failed answer, not silence.
  auto early = makeRequest(1, committed, target);
  test_ctx.publish(mmh::channels::kPlanRequestEam, early);
  drain(*lcm);
  ASSERT_EQ(sink.results.size(), 1u);
  EXPECT_EQ(sink.results[0].status, mmh::plan_result_t::STATUS_FAILED);
  EXPECT_EQ(sink.results[0].reason, mmh::plan_result_t::REASON_NO_MAP);

  // A pillar appears across the committed trajectory.
  mmh::VoxelGrid grid = eam_test::freeGrid();
  eam_test::addPillar(grid, 5.0, 0.05, 0.5);
  mmh::local_map_t map = mmh::makeKeyframe(grid, 1);
  map.header.utime = 1'900'000;
  test_ctx.publish(mmh::channels::kLocalMap, map);
  drain(*lcm);
  ASSERT_TRUE(node.map().hasMap());

  auto req = makeRequest(2, committed, target);
  test_ctx.publish(mmh::channels::kPlanRequestEam, req);
  drain(*lcm);
  ASSERT_EQ(sink.results.size(), 2u);
  const mmh::plan_result_t& res = sink.results[1];
  ASSERT_EQ(res.status, mmh::plan_result_t::STATUS_OK) << res.detail;
  EXPECT_EQ(res.request_id, 2);
  EXPECT_EQ(res.mode, mmh::plan_request_t::MODE_EAM);
  EXPECT_EQ(res.reason, mmh::plan_result_t::REASON_NONE);
  EXPECT_EQ(res.map_seq, 1);
  EXPECT_FALSE(res.narrow);
  EXPECT_GT(res.compute_us, 0);
  EXPECT_GT(res.cost_control, 0.0);
  EXPECT_EQ(res.trajectory.start_utime, req.start_utime);
  EXPECT_EQ(res.trajectory.source_mode, mmh::plan_request_t::MODE_EAM);
  EXPECT_NE(res.trajectory.trajectory_id, 0);
  std::string why;
  EXPECT_TRUE(mmh::validate(res, &why)) << why;
  const mmh::Trajectory t = mmh::fromMsg(res.trajectory);
  const mmh::KinematicState s = mmh::startStateOf(req);
  EXPECT_LT((t.position(0.0) - s.position).norm(), 1e-9);
  EXPECT_LT((t.velocity(0.0) - s.velocity).norm(), 1e-9);
  EXPECT_LT((t.acceleration(0.0) - s.acceleration).norm(), 1e-8);
  EXPECT_LT((t.position(t.duration()) - target).norm(), 1e-9);
  EXPECT_EQ(eam_test::firstBlockedTime(grid, t, false), -1.0);
  // Cost breakdown: control = the answer's jerk energy (checked with Trajectory's own
  // integral), no time term, penalties within the total.
  EXPECT_NEAR(res.cost_control, t.jerkEnergy(), 1e-6 * (1.0 + t.jerkEnergy()));
  EXPECT_EQ(res.cost_time, 0.0);
  EXPECT_GE(res.cost_penalty, 0.0);
  EXPECT_LE(res.cost_penalty, res.cost_total + 1e-9);
  EXPECT_EQ(node_ctx.counter("plans_ok"), 1);
}

TEST(EamNode, ReportsTheNarrowFlagAndRejectsBadRequests) {
  auto lcm = mmh::openLcm("memq://");
  mmh::ServiceContext node_ctx(*lcm, "mmh-eam", "");
  mmh::ServiceContext test_ctx(*lcm, "test", "");
  mmh::EamNode node(node_ctx, config());
  ResultSink sink;
  test_ctx.subscribe(mmh::channels::kPlanResult, &ResultSink::onResult, &sink);

  mmh::VoxelGrid grid = eam_test::freeGrid();
  eam_test::addWallWithGap(grid, 5.0, 0.3, 1.0, 1.0);
  mmh::local_map_t map = mmh::makeKeyframe(grid, 4);
  map.header.utime = 1'000'000;
  test_ctx.publish(mmh::channels::kLocalMap, map);

  const Vector3d start(0, 0, 1.2), target(10, 0, 1.2);
  const mmh::Trajectory committed = eam_test::straightLine(start, target, 7.0);
  auto req = makeRequest(10, committed, target);
  test_ctx.publish(mmh::channels::kPlanRequestEam, req);

  auto wrong_mode = makeRequest(11, committed, target);
  wrong_mode.mode = mmh::plan_request_t::MODE_SOM;
  test_ctx.publish(mmh::channels::kPlanRequestEam, wrong_mode);

  auto in_obstacle = makeRequest(12, committed, Vector3d(5.1, 0.0, 1.2));
  test_ctx.publish(mmh::channels::kPlanRequestEam, in_obstacle);

  auto nan = makeRequest(13, committed, target);
  nan.start_velocity[0] = NAN;  // dropped by the runtime's validation, counted
  test_ctx.publish(mmh::channels::kPlanRequestEam, nan);
  drain(*lcm);

  ASSERT_EQ(sink.results.size(), 3u);
  EXPECT_EQ(sink.results[0].request_id, 10);
  ASSERT_EQ(sink.results[0].status, mmh::plan_result_t::STATUS_OK) << sink.results[0].detail;
  EXPECT_TRUE(sink.results[0].narrow);
  EXPECT_EQ(sink.results[0].map_seq, 4);
  EXPECT_EQ(eam_test::firstBlockedTime(grid, mmh::fromMsg(sink.results[0].trajectory), false),
            -1.0);
  EXPECT_EQ(sink.results[1].request_id, 11);
  EXPECT_EQ(sink.results[1].reason, mmh::plan_result_t::REASON_BAD_INPUT);
  EXPECT_EQ(sink.results[2].request_id, 12);
  EXPECT_EQ(sink.results[2].reason, mmh::plan_result_t::REASON_TARGET_IN_OBSTACLE);
  EXPECT_EQ(sink.results[2].trajectory.num_pieces, 0);
  EXPECT_EQ(node_ctx.counter("rejected_invalid"), 1);
  EXPECT_EQ(node_ctx.counter("narrow_weights"), 1);
}
