// SomNode over LCM's in-process memq:// provider: LOCAL_MAP + PLAN_REQUEST_SOM in, one
// PLAN_RESULT out per request, with the contract's fields and reason codes.
#include <gtest/gtest.h>

#include <cmath>

#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/msg_convert.hpp"
#include "som_node.hpp"
#include "som_test_worlds.hpp"

using Eigen::Vector3d;

namespace {

struct ResultSink {
  void on(const mmh::plan_result_t& r) { results.push_back(r); }
  std::vector<mmh::plan_result_t> results;
};

void drain(lcm::LCM& lcm) {
  while (lcm.handleTimeout(0) > 0) {
  }
}

mmh::Config nodeConfig() {
  return mmh::Config::loadFile(std::string(MMH_SOURCE_DIR) + "/deploy/config/default.yaml");
}

mmh::plan_request_t request(int64_t id, const Vector3d& start, const Vector3d& target) {
  mmh::plan_request_t r{};
  r.header.utime = 1'000'000 + id;
  r.request_id = id;
  r.mode = mmh::plan_request_t::MODE_SOM;
  r.start_utime = 2'000'000 + id;
  mmh::KinematicState s;
  s.position = start;
  s.velocity = Vector3d(1.0, 0.0, 0.0);
  mmh::setStartState(s, r);
  mmh::fromVec3(target, r.target);
  mmh::fromVec3(target, r.goal);
  r.deadline_utime = 3'000'000;
  r.map_seq = 1;
  r.num_waypoints = 0;
  r.reference.num_pieces = 0;
  return r;
}

class SomNodeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    lcm_ = mmh::openLcm("memq://");
    node_ctx_ = std::make_unique<mmh::ServiceContext>(*lcm_, "mmh-som", "T_");
    node_ = std::make_unique<mmh::SomNode>(*node_ctx_, nodeConfig());
    test_ctx_ = std::make_unique<mmh::ServiceContext>(*lcm_, "tester", "T_");
    test_ctx_->subscribe(mmh::channels::kPlanResult, &ResultSink::on, &sink_);
  }
  void sendMap(const som_test::World& w, int64_t seq = 1) {
    mmh::local_map_t map = mmh::makeKeyframe(*w.grid, seq);
    map.header.utime = 500'000 + seq;
    test_ctx_->publish(mmh::channels::kLocalMap, map);
    drain(*lcm_);
  }
  std::unique_ptr<lcm::LCM> lcm_;
  std::unique_ptr<mmh::ServiceContext> node_ctx_, test_ctx_;
  std::unique_ptr<mmh::SomNode> node_;
  ResultSink sink_;
};

}  // namespace

TEST_F(SomNodeTest, AnswersWithAVerifiedTrajectory) {
  const auto w = som_test::sBend();
  sendMap(w);
  auto req = request(7, w.start, w.target);
  test_ctx_->publish(mmh::channels::kPlanRequestSom, req);
  drain(*lcm_);
  ASSERT_EQ(sink_.results.size(), 1u);
  const mmh::plan_result_t& r = sink_.results[0];
  EXPECT_EQ(r.status, mmh::plan_result_t::STATUS_OK) << r.detail;
  EXPECT_EQ(r.reason, mmh::plan_result_t::REASON_NONE);
  EXPECT_EQ(r.request_id, 7);
  EXPECT_EQ(r.mode, mmh::plan_request_t::MODE_SOM);
  EXPECT_EQ(r.map_seq, 1);
  EXPECT_GT(r.compute_us, 0);
  EXPECT_EQ(r.header.source, "mmh-som");
  EXPECT_EQ(r.trajectory.start_utime, req.start_utime);
  EXPECT_EQ(r.trajectory.source_mode, mmh::plan_request_t::MODE_SOM);
  EXPECT_GT(r.cost_time, 0.0);
  EXPECT_GT(r.cost_control, 0.0);
  EXPECT_NEAR(r.cost_total, r.cost_control + r.cost_time + r.cost_penalty, 1e-6 * r.cost_total);
  EXPECT_NE(r.detail.find("corridor"), std::string::npos);  // the split timings
  const mmh::Trajectory t = mmh::fromMsg(r.trajectory);
  ASSERT_FALSE(t.empty());
  EXPECT_EQ(t.position(0), w.start);
  EXPECT_EQ(t.velocity(0), Vector3d(1.0, 0.0, 0.0));
  EXPECT_LT((t.position(t.duration()) - w.target).norm(), 1e-3);
  EXPECT_LE(t.maxSpeed(), 3.0 * 1.01);
  EXPECT_LE(t.maxAcceleration(), 2.0 * 1.01);
  for (double s = 0.0; s <= t.duration(); s += 0.002)
    ASSERT_FALSE(w.grid->isOccupiedPoint(t.position(s))) << s;
  EXPECT_EQ(node_ctx_->counter("plans_ok"), 1);
}

TEST_F(SomNodeTest, NoMapYet) {
  const auto w = som_test::pillars();
  auto req = request(1, w.start, w.target);
  test_ctx_->publish(mmh::channels::kPlanRequestSom, req);
  drain(*lcm_);
  ASSERT_EQ(sink_.results.size(), 1u);
  EXPECT_EQ(sink_.results[0].status, mmh::plan_result_t::STATUS_FAILED);
  EXPECT_EQ(sink_.results[0].reason, mmh::plan_result_t::REASON_NO_MAP);
  EXPECT_EQ(sink_.results[0].trajectory.num_pieces, 0);
}

TEST_F(SomNodeTest, FailuresCarryTheirReason) {
  const auto w = som_test::targetEnclosed();
  sendMap(w);
  auto enclosed = request(1, w.start, w.target);
  test_ctx_->publish(mmh::channels::kPlanRequestSom, enclosed);
  auto in_obstacle = request(2, Vector3d(12.0, 1.1, 1.2), Vector3d(4, 0, 1.2));  // in the wall
  test_ctx_->publish(mmh::channels::kPlanRequestSom, in_obstacle);
  drain(*lcm_);
  ASSERT_EQ(sink_.results.size(), 2u);
  EXPECT_EQ(sink_.results[0].reason, mmh::plan_result_t::REASON_NO_PATH);
  EXPECT_EQ(sink_.results[1].reason, mmh::plan_result_t::REASON_START_IN_OBSTACLE);
  for (const auto& r : sink_.results) {
    EXPECT_EQ(r.status, mmh::plan_result_t::STATUS_FAILED);
    EXPECT_EQ(r.trajectory.num_pieces, 0);
    EXPECT_FALSE(r.detail.empty());
  }
  EXPECT_EQ(node_ctx_->counter("plans_failed"), 2);
}

TEST_F(SomNodeTest, NaNRequestIsRejectedWithoutCrash) {
  const auto w = som_test::pillars();
  sendMap(w);
  // Over LCM the runtime's validation drops it (counted) before the node sees it...
  auto bad = request(3, w.start, w.target);
  bad.start_position[1] = std::nan("");
  test_ctx_->publish(mmh::channels::kPlanRequestSom, bad);
  drain(*lcm_);
  EXPECT_TRUE(sink_.results.empty());
  EXPECT_EQ(node_ctx_->counter("rejected_invalid"), 1);
  // ... and handed to the node directly it is answered with REASON_BAD_INPUT.
  node_->onPlanRequest(bad);
  drain(*lcm_);
  ASSERT_EQ(sink_.results.size(), 1u);
  EXPECT_EQ(sink_.results[0].reason, mmh::plan_result_t::REASON_BAD_INPUT);
  // A request for another mode is refused too.
  auto other = request(4, w.start, w.target);
  other.mode = mmh::plan_request_t::MODE_EAM;
  node_->onPlanRequest(other);
  drain(*lcm_);
  ASSERT_EQ(sink_.results.size(), 2u);
  EXPECT_EQ(sink_.results[1].reason, mmh::plan_result_t::REASON_BAD_INPUT);
}

TEST_F(SomNodeTest, TheDetailSaysWhenThePathThatKeepsClearWasTaken) {
  // Hand-made worlds and random forests until the node has both taken the path that keeps clear
  // and kept the shortest one: its detail names the first only.
  const std::string note = "along the path that keeps clear (cheaper)";
  bool seen_taken = false, seen_kept = false;
  int64_t id = 1;
  std::vector<som_test::World> worlds{som_test::wallWithGap(), som_test::sBend(),
                                      som_test::pillars()};
  for (unsigned seed = 20261207; seed < 20261227; ++seed)
    worlds.push_back(som_test::randomPillars(seed));
  for (size_t k = 0; k < worlds.size() && !(seen_taken && seen_kept); ++k) {
    const som_test::World& w = worlds[k];
    if (w.grid->isBlockedPoint(w.start) || w.grid->isBlockedPoint(w.target)) continue;
    sink_.results.clear();
    sendMap(w, id);  // a new keyframe per world
    auto req = request(id, w.start, w.target);
    req.map_seq = id++;
    test_ctx_->publish(mmh::channels::kPlanRequestSom, req);
    drain(*lcm_);
    ASSERT_EQ(sink_.results.size(), 1u);
    if (sink_.results[0].status != mmh::plan_result_t::STATUS_OK) continue;
    const bool taken = node_->lastOutput().clearance_taken > 0;
    EXPECT_EQ(sink_.results[0].detail.find(note) != std::string::npos, taken)
        << "world " << k << ": " << sink_.results[0].detail;
    (taken ? seen_taken : seen_kept) = true;
  }
  EXPECT_TRUE(seen_taken);
  EXPECT_TRUE(seen_kept);
}
