// The latency monitor and the latency budget rule, against known answers.
#include <gtest/gtest.h>

#include <cmath>

#include "mmh/arbiter/latency_monitor.hpp"
#include "mmh/arbiter/replan_rules.hpp"

using namespace mmh::arbiter;

namespace {
constexpr int64_t kT0 = 5'000'000'000;
int64_t at(double seconds) {
  return kT0 + static_cast<int64_t>(seconds * 1e6);
}
}  // namespace

TEST(LatencyMonitor, PercentilesOfAnswersPerModeByNearestRank) {
  LatencyMonitor m(10.0);
  // SOM answers after 10, 20, ..., 100 ms; one EAM answer after 5 ms.
  for (int i = 1; i <= 10; ++i) {
    m.onRequest(i, Mode::kSom, at(i));
    EXPECT_NEAR(m.onAnswer(i, at(i + 0.01 * i)), 0.01 * i, 1e-9);
  }
  m.onRequest(100, Mode::kEam, at(11));
  m.onAnswer(100, at(11.005));
  EXPECT_EQ(m.samples(Mode::kSom), 10);
  EXPECT_NEAR(m.answerLatency(Mode::kSom, 0.5), 0.05, 1e-9);
  EXPECT_NEAR(m.answerLatency(Mode::kSom, 0.99), 0.10, 1e-9);
  EXPECT_NEAR(m.answerLatency(Mode::kEam, 0.99), 0.005, 1e-9);
  EXPECT_NEAR(m.worstAnswerLatency(0.99), 0.10, 1e-9);
  EXPECT_EQ(m.answerLatency(Mode::kFpm, 0.99), 0.0);  // no samples
}

TEST(LatencyMonitor, UnknownAndRepeatedAnswersAreNotMeasured) {
  LatencyMonitor m(10.0);
  EXPECT_LT(m.onAnswer(7, at(1)), 0.0);
  m.onRequest(8, Mode::kFpm, at(1));
  EXPECT_GE(m.onAnswer(8, at(1.002)), 0.0);
  EXPECT_LT(m.onAnswer(8, at(1.5)), 0.0);  // a duplicate is not a second, slower answer
  EXPECT_EQ(m.samples(Mode::kFpm), 1);
}

TEST(LatencyMonitor, SamplesLeaveTheWindowSoTheLoadCanGo) {
  LatencyMonitor m(2.0);
  m.onRequest(1, Mode::kSom, at(0));
  m.onAnswer(1, at(0.3));
  m.onMapAge(0.4, at(0.3));
  m.expire(at(2.2));
  EXPECT_NEAR(m.answerLatency(Mode::kSom, 0.99), 0.3, 1e-9);
  EXPECT_NEAR(m.mapAge(0.99), 0.4, 1e-9);
  m.expire(at(2.4));
  EXPECT_EQ(m.samples(Mode::kSom), 0);
  EXPECT_EQ(m.mapAge(0.99), 0.0);
}

TEST(LatencyBudget, AnswersWithinTheDeadlineKeepTheConfiguredBudget) {
  ArbiterParams p;  // deadline 0.04 s, lead 0.05 s, headroom 1.5
  const LatencyBudget b = latencyBudget(0.02, 0.05, p);
  EXPECT_EQ(b.answer_deadline_s, p.answer_deadline_s);
  EXPECT_EQ(b.replan_lead_s, p.replan_lead_s);
  EXPECT_FALSE(b.degraded);
  EXPECT_TRUE(b.why.empty());
}

TEST(LatencyBudget, LateAnswersLengthenDeadlineAndLeadUpToTheCap) {
  ArbiterParams p;
  const LatencyBudget b = latencyBudget(0.1, 0.0, p);
  EXPECT_EQ(b.answer_latency_p99_s, 0.1);         // what the budget was made from, for HEARTBEAT
  EXPECT_NEAR(b.answer_deadline_s, 0.15, 1e-12);  // 1.5 x 0.1 s
  EXPECT_NEAR(b.replan_lead_s, 0.16, 1e-12);      // keeps its 10 ms over the deadline
  EXPECT_TRUE(b.degraded);
  EXPECT_NE(b.why.find("answers late"), std::string::npos);
  EXPECT_EQ(b.speed_limit_mps, p.max_vel_mps);  // within the full-speed deadline
  const LatencyBudget capped = latencyBudget(2.0, 0.0, p);
  EXPECT_NEAR(capped.answer_deadline_s, p.max_slowed_answer_deadline_s, 1e-12);
  EXPECT_NEAR(capped.replan_lead_s, p.max_slowed_answer_deadline_s + 0.01, 1e-12);
}

// Defaults: 3 m/s, 2 m/s^2, a 4.5 m sensor, maps up to stale_map_s = 0.5 s old. Up to the
// full-speed deadline (0.2 s) the vehicle may fly at full speed; past it the speed comes down so
// that reacting for the lead and the map's age and then braking still ends within the sensor's
// range, and returns when the answers are fast again.
TEST(LatencyBudget, AnswersLaterThanTheFullSpeedDeadlineLowerTheSpeed) {
  ArbiterParams p;
  const double full_speed_p99 = p.max_answer_deadline_s / p.latency_headroom;
  EXPECT_EQ(latencyBudget(full_speed_p99, 0.0, p).speed_limit_mps, p.max_vel_mps);
  double previous = p.max_vel_mps;
  for (double p99 : {0.2, 0.4, 0.6}) {
    const LatencyBudget b = latencyBudget(p99, 0.0, p);
    EXPECT_NEAR(b.answer_deadline_s, p.latency_headroom * p99, 1e-12);
    EXPECT_LT(b.speed_limit_mps, previous) << p99;
    EXPECT_GT(b.speed_limit_mps, 0.5) << p99;
    // The stop after the reaction ends exactly at the sensor's range.
    const double v = b.speed_limit_mps;
    EXPECT_NEAR(v * v / (2.0 * p.max_acc_mps2) + v * (b.replan_lead_s + p.stale_map_s),
                p.sensor_range_m, 1e-9);
    EXPECT_TRUE(b.degraded);
    EXPECT_NE(b.why.find("speed lowered to"), std::string::npos) << b.why;
    previous = v;
  }
  // 0.6 s x 1.5 = 0.9 s deadline, 0.91 s lead: v^2 / 4 + 1.41 v = 4.5 gives 2.39 m/s.
  EXPECT_NEAR(latencyBudget(0.6, 0.0, p).speed_limit_mps,
              2.0 * (std::sqrt(1.41 * 1.41 + 4.5) - 1.41), 1e-9);
  EXPECT_EQ(latencyBudget(0.01, 0.0, p).speed_limit_mps, p.max_vel_mps);
}

TEST(LatencyBudget, LateMapsAreDegradedWithoutChangingTheBudget) {
  ArbiterParams p;
  const LatencyBudget b = latencyBudget(0.0, 0.4, p);
  EXPECT_TRUE(b.degraded);
  EXPECT_EQ(b.answer_deadline_s, p.answer_deadline_s);
  EXPECT_NE(b.why.find("LOCAL_MAP late"), std::string::npos);
}
