// The LCM runtime over memq:// (in-process): decoding, validation, counters, prefixes, clock.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <thread>

#include "mmh/common/lcm_runtime.hpp"
#include "mmh/goal_t.hpp"
#include "mmh/odometry_t.hpp"

namespace {

struct Sink {
  void onGoal(const mmh::goal_t& m) { goals.push_back(m); }
  void onOdom(const mmh::odometry_t& m) { odoms.push_back(m); }
  std::vector<mmh::goal_t> goals;
  std::vector<mmh::odometry_t> odoms;
};

void drain(lcm::LCM& lcm) {
  while (lcm.handleTimeout(0) > 0) {
  }
}

mmh::odometry_t odom(int64_t utime) {
  mmh::odometry_t m{};
  m.header.utime = utime;
  m.orientation[0] = 1.0;
  return m;
}

}  // namespace

TEST(Runtime, OpenLcmMemq) {
  auto lcm = mmh::openLcm("memq://");
  EXPECT_TRUE(lcm->good());
}

TEST(Runtime, PublishSubscribeWithPrefixSeqAndClock) {
  auto lcm = mmh::openLcm("memq://");
  mmh::ServiceContext pub(*lcm, "pub", "UAV1_");
  mmh::ServiceContext sub(*lcm, "sub", "UAV1_");
  mmh::ServiceContext other(*lcm, "other", "UAV2_");
  Sink sink, other_sink;
  sub.subscribe(mmh::channels::kOdometry, &Sink::onOdom, &sink);
  other.subscribe(mmh::channels::kOdometry, &Sink::onOdom, &other_sink);
  for (int i = 1; i <= 3; ++i) {
    auto m = odom(1000 * i);
    pub.publish(mmh::channels::kOdometry, m);
  }
  drain(*lcm);
  ASSERT_EQ(sink.odoms.size(), 3u);
  EXPECT_EQ(sink.odoms[2].header.seq, 3);
  EXPECT_EQ(sink.odoms[2].header.source, "pub");
  EXPECT_TRUE(other_sink.odoms.empty());  // prefixes isolate vehicles
  EXPECT_EQ(sub.clock().now(), 3000);
  EXPECT_EQ(sub.messagesIn(), 3);
  EXPECT_EQ(pub.messagesOut(), 3);
}

TEST(Runtime, RejectsInvalidWrongTypeAndBackwardsTime) {
  auto lcm = mmh::openLcm("memq://");
  mmh::ServiceContext pub(*lcm, "pub", "");
  mmh::ServiceContext sub(*lcm, "sub", "");
  Sink sink;
  sub.subscribe(mmh::channels::kOdometry, &Sink::onOdom, &sink);
  auto bad = odom(10);
  bad.position[0] = NAN;
  pub.publish(mmh::channels::kOdometry, bad);
  mmh::goal_t wrong{};  // a goal on the odometry channel
  pub.publish(mmh::channels::kOdometry, wrong);
  auto a = odom(5000), b = odom(4000);
  pub.publish(mmh::channels::kOdometry, a);
  pub.publish(mmh::channels::kOdometry, b);
  drain(*lcm);
  ASSERT_EQ(sink.odoms.size(), 1u);
  EXPECT_EQ(sink.odoms[0].header.utime, 5000);
  EXPECT_EQ(sub.counter("rejected_invalid"), 1);
  EXPECT_EQ(sub.counter("rejected_decode"), 1);
  EXPECT_EQ(sub.counter("rejected_time_backwards"), 1);
  EXPECT_EQ(sub.messagesRejected(), 3);
}

TEST(Runtime, HeartbeatCarriesCounters) {
  auto lcm = mmh::openLcm("memq://");
  mmh::ServiceContext svc(*lcm, "mmh-test", "");
  mmh::ServiceContext mon(*lcm, "monitor", "");
  struct HbSink {
    void on(const mmh::heartbeat_t& h) { beats.push_back(h); }
    std::vector<mmh::heartbeat_t> beats;
  } hb;
  mon.subscribe(mmh::channels::kHeartbeat, &HbSink::on, &hb);
  svc.increment("rejected_nan", 2);
  svc.setState(mmh::heartbeat_t::STATE_DEGRADED, "no map");
  svc.maybePublishHeartbeat(1'000'000);
  svc.maybePublishHeartbeat(1'500'000);  // too soon
  svc.maybePublishHeartbeat(2'000'000);
  drain(*lcm);
  ASSERT_EQ(hb.beats.size(), 2u);
  EXPECT_EQ(hb.beats[0].service, "mmh-test");
  EXPECT_EQ(hb.beats[0].state, mmh::heartbeat_t::STATE_DEGRADED);
  ASSERT_EQ(hb.beats[0].num_counters, 1);
  EXPECT_EQ(hb.beats[0].counter_names[0], "rejected_nan");
  EXPECT_EQ(hb.beats[0].counter_values[0], 2);
}

TEST(Runtime, AServiceThatRunsReportsOkUnlessItSaidOtherwise) {
  auto lcm = mmh::openLcm("memq://");
  mmh::ServiceContext svc(*lcm, "mmh-test", "");
  EXPECT_EQ(svc.state(), mmh::heartbeat_t::STATE_STARTING);
  svc.markRunning();
  EXPECT_EQ(svc.state(), mmh::heartbeat_t::STATE_OK);
  mmh::ServiceContext waiting(*lcm, "mmh-waiting", "");
  waiting.setState(mmh::heartbeat_t::STATE_DEGRADED, "waiting for LOCAL_MAP");
  waiting.markRunning();
  EXPECT_EQ(waiting.state(), mmh::heartbeat_t::STATE_DEGRADED);
}

TEST(Runtime, LossSwitchDropsAShare) {
  auto lcm = mmh::openLcm("memq://");
  mmh::ServiceContext pub(*lcm, "pub", "");
  mmh::ServiceContext sub(*lcm, "sub", "");
  Sink sink;
  sub.subscribe(mmh::channels::kGoal, &Sink::onGoal, &sink);
  sub.setIncomingLoss(mmh::channels::kGoal, 0.3, 42);
  for (int i = 1; i <= 1000; ++i) {
    mmh::goal_t g{};
    g.header.utime = i;
    pub.publish(mmh::channels::kGoal, g);
    drain(*lcm);
  }
  EXPECT_GT(sink.goals.size(), 600u);
  EXPECT_LT(sink.goals.size(), 800u);
  EXPECT_EQ(sub.counter("test_dropped") + static_cast<int64_t>(sink.goals.size()), 1000);
}

TEST(Runtime, LossSwitchFromTheEnvironment) {
  // How fault tests make separate processes lose LOCAL_MAP: the variable is read by every context.
  setenv("MMH_TEST_INCOMING_LOSS", "GOAL=1.0,ODOMETRY=oops", 1);
  auto lcm = mmh::openLcm("memq://");
  mmh::ServiceContext pub(*lcm, "pub", "");
  mmh::ServiceContext sub(*lcm, "sub", "");
  unsetenv("MMH_TEST_INCOMING_LOSS");
  Sink sink;
  sub.subscribe(mmh::channels::kGoal, &Sink::onGoal, &sink);
  sub.subscribe(mmh::channels::kOdometry, &Sink::onOdom, &sink);
  for (int i = 1; i <= 20; ++i) {
    mmh::goal_t g{};
    g.header.utime = i;
    pub.publish(mmh::channels::kGoal, g);
    mmh::odometry_t o = odom(i);
    pub.publish(mmh::channels::kOdometry, o);
    drain(*lcm);
  }
  EXPECT_TRUE(sink.goals.empty());
  EXPECT_EQ(sub.counter("test_dropped"), 20);
  EXPECT_EQ(sink.odoms.size(), 20u);  // a malformed item is ignored (with a warning)
}

TEST(Runtime, AJumpFarAheadOfTheMessageClockIsRefused) {
  auto lcm = mmh::openLcm("memq://");
  mmh::ServiceContext pub(*lcm, "pub", "");
  mmh::ServiceContext sub(*lcm, "sub", "");
  Sink sink;
  sub.subscribe(mmh::channels::kOdometry, &Sink::onOdom, &sink);
  for (int64_t utime :
       {int64_t{1'000'000}, int64_t{1'000'000} + 3600'000'000, int64_t{3'000'000}}) {
    mmh::odometry_t o = odom(utime);
    pub.publish(mmh::channels::kOdometry, o);
    drain(*lcm);
  }
  // The hour-ahead message would have made every real message look an hour old.
  ASSERT_EQ(sink.odoms.size(), 2u);
  EXPECT_EQ(sink.odoms[1].header.utime, 3'000'000);
  EXPECT_EQ(sub.counter("rejected_time_jump"), 1);
  EXPECT_EQ(sub.clock().now(), 3'000'000);
}

TEST(Runtime, AClockThatStaysAheadIsFollowedAfterTheResyncTime) {
  // A simulator starved of the CPU catches up: its clock jumps 11 s and goes on from there. Its
  // messages are refused as jumps at first; once they have stayed ahead for kClockResyncUs of
  // wall time, they are delivered again and the message clock follows.
  auto lcm = mmh::openLcm("memq://");
  mmh::ServiceContext pub(*lcm, "pub", "");
  mmh::ServiceContext sub(*lcm, "sub", "");
  Sink sink;
  sub.subscribe(mmh::channels::kOdometry, &Sink::onOdom, &sink);
  mmh::odometry_t first = odom(1'000'000);
  pub.publish(mmh::channels::kOdometry, first);
  drain(*lcm);
  const int64_t jumped = 1'000'000 + 11'000'000;
  const int64_t wall_start = mmh::wallTimeUs();
  int64_t utime = jumped;
  while (sink.odoms.size() < 2 &&
         mmh::wallTimeUs() - wall_start < 5 * mmh::ServiceContext::kClockResyncUs) {
    mmh::odometry_t o = odom(utime);
    pub.publish(mmh::channels::kOdometry, o);
    drain(*lcm);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    utime += 50'000;
  }
  ASSERT_EQ(sink.odoms.size(), 2u) << "the jumped clock was never followed";
  EXPECT_GE(sink.odoms[1].header.utime, jumped);
  EXPECT_GE(sub.counter("rejected_time_jump"), 1);
  EXPECT_EQ(sub.counter("clock_resyncs"), 1);
  EXPECT_EQ(sub.clock().now(), sink.odoms[1].header.utime);
  // From then on, the new clock's messages are plain input.
  mmh::odometry_t next = odom(utime + 50'000);
  pub.publish(mmh::channels::kOdometry, next);
  drain(*lcm);
  EXPECT_EQ(sink.odoms.size(), 3u);
  EXPECT_EQ(sub.counter("clock_resyncs"), 1);
}

TEST(Runtime, EstimatedNowGoesOnWithTheWallClockWhileInputsAreSilent) {
  auto lcm = mmh::openLcm("memq://");
  mmh::ServiceContext pub(*lcm, "pub", "");
  mmh::ServiceContext sub(*lcm, "sub", "");
  Sink sink;
  sub.subscribe(mmh::channels::kOdometry, &Sink::onOdom, &sink);
  EXPECT_EQ(sub.estimatedNow(mmh::wallTimeUs()), 0);  // no input yet: no clock to go on from
  const int64_t utime = 5'000'000;
  const int64_t wall_before = mmh::wallTimeUs();
  mmh::odometry_t o = odom(utime);
  pub.publish(mmh::channels::kOdometry, o);
  drain(*lcm);
  const int64_t wall_after = mmh::wallTimeUs();
  ASSERT_EQ(sink.odoms.size(), 1u);
  // Two seconds of silence after the input moved the clock (at some wall time between the two
  // readings): the estimate is the input's time plus the silence.
  const int64_t silent_us = 2'000'000;
  const int64_t estimate = sub.estimatedNow(wall_after + silent_us);
  EXPECT_GE(estimate, utime + silent_us);
  EXPECT_LE(estimate, utime + silent_us + (wall_after - wall_before));
  EXPECT_EQ(sub.clock().now(), utime);  // the message clock itself does not move
  // A wall clock behind the last input adds nothing.
  EXPECT_EQ(sub.estimatedNow(wall_before - 1'000'000), utime);
}

TEST(Runtime, AHeartbeatCarriesTheTimeItIsSentNotThatOfTheLastInput) {
  auto lcm = mmh::openLcm("memq://");
  mmh::ServiceContext pub(*lcm, "pub", "");
  mmh::ServiceContext idle(*lcm, "mmh-idle", "");
  mmh::ServiceContext mon(*lcm, "monitor", "");
  Sink sink;
  idle.subscribe(mmh::channels::kOdometry, &Sink::onOdom, &sink);
  struct HbSink {
    void on(const mmh::heartbeat_t& h) { beats.push_back(h); }
    std::vector<mmh::heartbeat_t> beats;
  } hb;
  mon.subscribe(mmh::channels::kHeartbeat, &HbSink::on, &hb);
  const int64_t utime = 5'000'000;
  mmh::odometry_t o = odom(utime);
  pub.publish(mmh::channels::kOdometry, o);
  drain(*lcm);
  const int64_t wall_input = mmh::wallTimeUs();
  // Sent by a real-time service 50 ms or more after its last input...
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  idle.publishHeartbeat();
  // ... and by a lock-step host at its simulated time.
  idle.maybePublishHeartbeat(9'000'000, 9'000'000);
  drain(*lcm);
  // A simulator moves its own clock (observe, no input); a stamp older than the last is not sent.
  mmh::ServiceContext sim(*lcm, "mmh-sim", "");
  sim.clock().observe(7'000'000);
  sim.publishHeartbeat();
  idle.maybePublishHeartbeat(10'000'000, 8'000'000);
  drain(*lcm);
  ASSERT_EQ(hb.beats.size(), 4u);
  EXPECT_GE(hb.beats[0].header.utime, utime + 50'000);
  EXPECT_LE(hb.beats[0].header.utime, utime + (mmh::wallTimeUs() - wall_input) + 1'000'000);
  EXPECT_EQ(hb.beats[1].header.utime, 9'000'000);
  EXPECT_GE(hb.beats[2].header.utime, 7'000'000);
  EXPECT_LE(hb.beats[2].header.utime, 8'000'000);
  EXPECT_EQ(hb.beats[3].header.utime, 9'000'000);
}
