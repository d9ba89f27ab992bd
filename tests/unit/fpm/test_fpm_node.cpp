// The FPM node over memq:// (in-process LCM): one PLAN_RESULT per PLAN_REQUEST_FPM.
#include <gtest/gtest.h>

#include <cmath>

#include "fpm_node.hpp"
#include "mmh/common/msg_convert.hpp"

using Eigen::Vector3d;
using mmh::plan_request_t;
using mmh::plan_result_t;

namespace {

struct Sink {
  void onResult(const plan_result_t& m) { results.push_back(m); }
  std::vector<plan_result_t> results;
};

class FpmNodeTest : public ::testing::Test {
 protected:
  FpmNodeTest()
      : lcm_(mmh::openLcm("memq://")),
        node_ctx_(*lcm_, "mmh-fpm", "T_"),
        test_ctx_(*lcm_, "test", "T_"),
        node_(node_ctx_, mmh::Config::loadFile(MMH_SOURCE_DIR "/deploy/config/default.yaml")) {
    test_ctx_.subscribe(mmh::channels::kPlanResult, &Sink::onResult, &sink_);
  }

  plan_request_t request(int64_t id, const Vector3d& target) {
    plan_request_t r{};
    r.header.utime = 1'000'000 + id;
    r.request_id = id;
    r.mode = plan_request_t::MODE_FPM;
    r.start_utime = 2'000'000 + id;
    mmh::KinematicState s;
    s.position = Vector3d(0, 0, 1.2);
    s.velocity = Vector3d(1.0, 0.2, 0.0);
    mmh::setStartState(s, r);
    mmh::fromVec3(target, r.target);
    mmh::fromVec3(target, r.goal);
    r.deadline_utime = r.start_utime;
    r.map_seq = 7;
    r.num_waypoints = 0;
    return r;
  }
  void send(plan_request_t r) {
    test_ctx_.publish(mmh::channels::kPlanRequestFpm, r);
    while (lcm_->handleTimeout(0) > 0) {
    }
  }

  std::unique_ptr<lcm::LCM> lcm_;
  mmh::ServiceContext node_ctx_, test_ctx_;
  mmh::FpmNode node_;
  Sink sink_;
};

}  // namespace

TEST_F(FpmNodeTest, AnswersARequestWithAFeasibleTrajectory) {
  send(request(5, Vector3d(12, 3, 1.5)));
  ASSERT_EQ(sink_.results.size(), 1u);
  const plan_result_t& r = sink_.results[0];
  EXPECT_EQ(r.request_id, 5);
  EXPECT_EQ(r.mode, plan_request_t::MODE_FPM);
  EXPECT_EQ(r.status, plan_result_t::STATUS_OK) << r.detail;
  EXPECT_EQ(r.reason, plan_result_t::REASON_NONE);
  EXPECT_EQ(r.map_seq, 7);
  EXPECT_GT(r.compute_us, 0);
  EXPECT_EQ(r.header.source, "mmh-fpm");
  EXPECT_EQ(r.trajectory.start_utime, 2'000'005);
  EXPECT_EQ(r.trajectory.source_mode, plan_request_t::MODE_FPM);
  EXPECT_EQ(r.trajectory.trajectory_id, 5);
  EXPECT_NEAR(r.cost_total, r.cost_control + r.cost_time + r.cost_penalty, 1e-6);
  const mmh::Trajectory t = mmh::fromMsg(r.trajectory);
  EXPECT_LT((t.position(0) - Vector3d(0, 0, 1.2)).norm(), 1e-9);
  EXPECT_LT((t.velocity(0) - Vector3d(1.0, 0.2, 0.0)).norm(), 1e-9);
  EXPECT_LT((t.position(t.duration()) - Vector3d(12, 3, 1.5)).norm(), 1e-6);
  EXPECT_LE(t.maxSpeed(), 3.0 + 1e-7);
  EXPECT_LE(t.maxAcceleration(), 2.0 + 1e-7);
  EXPECT_NEAR(r.cost_time, 20.0 * t.duration(), 1e-6);  // fpm.time_weight of the deployment
  EXPECT_EQ(node_ctx_.counter("planned_ok"), 1);
}

TEST_F(FpmNodeTest, FailuresAreAnsweredWithAReason) {
  send(request(6, Vector3d(50, 0, 1.2)));  // outside the geofence
  ASSERT_EQ(sink_.results.size(), 1u);
  EXPECT_EQ(sink_.results[0].status, plan_result_t::STATUS_FAILED);
  EXPECT_EQ(sink_.results[0].reason, plan_result_t::REASON_TARGET_OUT_OF_BOUNDS);
  EXPECT_EQ(sink_.results[0].trajectory.num_pieces, 0);
  auto fast = request(7, Vector3d(10, 0, 1.2));
  fast.start_velocity[0] = 5.0;
  send(fast);
  ASSERT_EQ(sink_.results.size(), 2u);
  EXPECT_EQ(sink_.results[1].reason, plan_result_t::REASON_INFEASIBLE_START);
  auto wrong_mode = request(8, Vector3d(10, 0, 1.2));
  wrong_mode.mode = plan_request_t::MODE_SOM;
  send(wrong_mode);
  ASSERT_EQ(sink_.results.size(), 3u);
  EXPECT_EQ(sink_.results[2].reason, plan_result_t::REASON_BAD_INPUT);
  EXPECT_EQ(node_ctx_.counter("failed_reason_5"), 1);
}

TEST_F(FpmNodeTest, NonFiniteRequestsAreRejectedByTheRuntimeWithoutCrashing) {
  auto bad = request(9, Vector3d(10, 0, 1.2));
  bad.target[1] = std::nan("");
  send(bad);
  auto inf = request(10, Vector3d(10, 0, 1.2));
  inf.start_acceleration[2] = INFINITY;
  send(inf);
  EXPECT_TRUE(sink_.results.empty());
  EXPECT_EQ(node_ctx_.counter("rejected_invalid"), 2);
  // The service still answers the next good request.
  send(request(11, Vector3d(10, 0, 1.2)));
  ASSERT_EQ(sink_.results.size(), 1u);
  EXPECT_EQ(sink_.results[0].status, plan_result_t::STATUS_OK);
}
