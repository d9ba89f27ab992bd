// The census of stops and stalls on hand-made message sequences: the cause of each stop, the
// failed modes before it, the longest run of calls without a commit, the longest time without
// progress toward the goal.
#include <gtest/gtest.h>

#include "mmh/arbiter_status_t.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/plan_result_t.hpp"
#include "stop_census.hpp"

namespace mmh {
namespace {

constexpr int kSom = plan_request_t::MODE_SOM, kEam = plan_request_t::MODE_EAM;
constexpr int kFpm = plan_request_t::MODE_FPM;

DecisionSample decision(double t, int outcome, int trigger, int modes_asked,
                        const std::string& detail) {
  DecisionSample d;
  d.time_s = t;
  d.outcome = outcome;
  d.trigger = trigger;
  d.modes_asked = modes_asked;
  d.detail = detail;
  return d;
}

TEST(StopCause, NamesEachKindOfStop) {
  EXPECT_EQ(stopCause("LOCAL_MAP is stale: stopping until maps return"), "stale map");
  EXPECT_EQ(stopCause("ODOMETRY is stale (312 ms old): no planning until it returns; stopping"),
            "stale odometry");
  EXPECT_EQ(stopCause("no usable answer and danger ahead: SOM failed (no path); "),
            "no usable answer + danger ahead");
  EXPECT_EQ(stopCause("no usable answer and unmapped space within stopping reach: EAM rejected: "
                      "enters unmapped space 0.40 s from its start; "),
            "no usable answer + unmapped space ahead");
  EXPECT_EQ(stopCause("no usable answer and danger ahead: SOM failed (x); no answer by the "
                      "deadline; "),
            "deadline");
  EXPECT_EQ(stopCause("no usable answer and danger ahead: answer came after its start time; "),
            "late answer");
  EXPECT_EQ(stopCause("no usable answer and danger ahead: ODOMETRY is stale: answer not "
                      "committed; "),
            "stale odometry");
  EXPECT_EQ(stopCause("something new"), "other");
}

TEST(StopCensus, StopAfterAFailedRoundNamesItsModesAndCause) {
  StopCensusBuilder b;
  // A committed round, then two failed rounds of SOM + EAM; the second ends in a stop.
  b.onPlanResult(kFpm, true, plan_result_t::REASON_NONE, "");
  b.onDecision(decision(0.5, arbiter_status_t::OUTCOME_COMMITTED, 1, 1 << kFpm, "committed FPM"));
  b.onPlanResult(kSom, false, plan_result_t::REASON_CORRIDOR, "corridor: start not free");
  b.onPlanResult(kEam, false, plan_result_t::REASON_OPTIMIZER, "did not converge");
  b.onDecision(decision(3.0, arbiter_status_t::OUTCOME_FAILED, 3, (1 << kSom) | (1 << kEam),
                        "SOM failed (corridor); EAM failed (did not converge); "));
  b.onPlanResult(kSom, false, plan_result_t::REASON_NO_PATH, "A* found no path");
  b.onPlanResult(kEam, true, plan_result_t::REASON_NONE, "");
  const std::string notes =
      "SOM failed (A* found no path); EAM rejected: collides with the arbiter's map 0.31 s from "
      "its start, at (1.20, -0.40, 1.10); ";
  b.onDecision(
      decision(3.2, arbiter_status_t::OUTCOME_FAILED, 5, (1 << kSom) | (1 << kEam), notes));
  b.onDecision(decision(3.2, arbiter_status_t::OUTCOME_STOPPING, 5, 0,
                        "no usable answer and danger ahead: " + notes));
  const FlightCensus c = b.finish(4.0);
  ASSERT_EQ(c.stops.size(), 1u);
  const StopRecord& s = c.stops[0];
  EXPECT_DOUBLE_EQ(s.time_s, 3.2);
  EXPECT_EQ(s.trigger, "retry");
  EXPECT_EQ(s.cause, "no usable answer + danger ahead");
  EXPECT_EQ(s.failed_decisions_before, 2);
  ASSERT_EQ(s.failed_modes.size(), 2u);
  EXPECT_EQ(s.failed_modes[0].mode, "SOM");
  EXPECT_EQ(s.failed_modes[0].reason, "no path");
  EXPECT_EQ(s.failed_modes[0].text, "A* found no path");
  EXPECT_EQ(s.failed_modes[1].mode, "EAM");
  EXPECT_EQ(s.failed_modes[1].reason, "rejected: collides with the arbiter's map");
  EXPECT_EQ(s.failed_modes[1].text,
            "collides with the arbiter's map 0.31 s from its start, at (1.20, -0.40, 1.10)");
  EXPECT_EQ(c.max_calls_without_commit, 4);
  EXPECT_EQ(c.causeCounts().at("no usable answer + danger ahead"), 1);
}

TEST(StopCensus, VerificationFailuresCountByWhatTheyFound) {
  StopCensusBuilder b;
  b.onPlanResult(kSom, false, plan_result_t::REASON_VERIFY,
                 "verification: max acceleration 2.419 m/s^2 exceeds 2 [A* 0.33 ms]");
  b.onPlanResult(kEam, false, plan_result_t::REASON_VERIFY,
                 "verification: leaves the corridor by 0.02 m in piece 0 [A* 4.27 ms]");
  const std::string notes = "SOM failed (verification: ...); EAM failed (verification: ...); ";
  b.onDecision(
      decision(2.0, arbiter_status_t::OUTCOME_FAILED, 5, (1 << kSom) | (1 << kEam), notes));
  b.onDecision(decision(2.0, arbiter_status_t::OUTCOME_STOPPING, 5, 0,
                        "no usable answer and danger ahead: " + notes));
  const FlightCensus c = b.finish(3.0);
  ASSERT_EQ(c.stops.size(), 1u);
  ASSERT_EQ(c.stops[0].failed_modes.size(), 2u);
  EXPECT_EQ(c.stops[0].failed_modes[0].reason, "verify: max acceleration");
  EXPECT_EQ(c.stops[0].failed_modes[1].reason, "verify: leaves the corridor");
}

TEST(StopCensus, UnansweredModesAndStaleMapStops) {
  StopCensusBuilder b;
  b.onPlanResult(kSom, false, plan_result_t::REASON_NO_MAP, "no map");
  b.onDecision(decision(1.0, arbiter_status_t::OUTCOME_FAILED, 5, (1 << kSom) | (1 << kEam),
                        "SOM failed (no map); no answer by the deadline; "));
  b.onDecision(decision(1.0, arbiter_status_t::OUTCOME_STOPPING, 5, 0,
                        "no usable answer and danger ahead: SOM failed (no map); no answer by "
                        "the deadline; "));
  // Seconds later, a stop of its own: no failed round belongs to it.
  b.onDecision(decision(5.0, arbiter_status_t::OUTCOME_STOPPING, 0, 0,
                        "LOCAL_MAP is stale: stopping until maps return"));
  const FlightCensus c = b.finish(6.0);
  ASSERT_EQ(c.stops.size(), 2u);
  EXPECT_EQ(c.stops[0].cause, "deadline");
  EXPECT_EQ(c.stops[0].trigger, "retry");
  ASSERT_EQ(c.stops[0].failed_modes.size(), 2u);
  EXPECT_EQ(c.stops[0].failed_modes[1].mode, "EAM");
  EXPECT_EQ(c.stops[0].failed_modes[1].reason, "no answer");
  EXPECT_EQ(c.stops[1].cause, "stale map");
  EXPECT_TRUE(c.stops[1].failed_modes.empty());
  EXPECT_EQ(c.causeCounts().at("deadline"), 1);
  EXPECT_EQ(c.causeCounts().at("stale map"), 1);
}

TEST(StopCensus, CallsWithoutCommitRestartAtEachCommitAndCountAnOpenRound) {
  StopCensusBuilder b;
  auto failedRound = [&](double t, int calls) {
    for (int i = 0; i < calls; ++i) b.onPlanResult(kSom, false, plan_result_t::REASON_NO_PATH, "");
    b.onDecision(decision(t, arbiter_status_t::OUTCOME_FAILED, 5, 1 << kSom, "SOM failed (x); "));
  };
  failedRound(1.0, 2);
  failedRound(1.2, 1);  // 3 in a row
  b.onPlanResult(kSom, false, plan_result_t::REASON_NO_PATH, "");
  b.onPlanResult(kEam, true, plan_result_t::REASON_NONE, "");
  b.onDecision(decision(1.4, arbiter_status_t::OUTCOME_COMMITTED, 5, (1 << kSom) | (1 << kEam),
                        "SOM failed (x); committed EAM"));
  failedRound(2.0, 1);
  EXPECT_EQ(b.finish(3.0).max_calls_without_commit, 3);
  // An open round at the end: its calls have no commit either (1 + 3 = 4).
  for (int i = 0; i < 3; ++i) b.onPlanResult(kEam, false, plan_result_t::REASON_OPTIMIZER, "");
  EXPECT_EQ(b.finish(3.0).max_calls_without_commit, 4);
  // Answers of modes that are not planners (the stop) are not planning calls.
  b.onPlanResult(plan_request_t::MODE_STOP, true, 0, "");
  EXPECT_EQ(b.finish(3.0).max_calls_without_commit, 4);
  // A round that keeps the committed trajectory (a later halfway answer) ends the run: the
  // open round's calls close with it, and the three after it make no run longer than 3.
  b.onDecision(decision(2.4, arbiter_status_t::OUTCOME_KEPT, 2, 1 << kEam, "kept"));
  failedRound(2.6, 3);
  EXPECT_EQ(b.finish(3.0).max_calls_without_commit, 3);
}

TEST(StopCensus, AStopHoldsUntilTheNextCommitAndKnowsWhetherTheVehicleCameToRest) {
  StopCensusBuilder b;
  b.onProgress(0.0, 40.0, 3.0);
  b.onDecision(decision(0.1, arbiter_status_t::OUTCOME_COMMITTED, 1, 1 << kFpm, "committed"));
  b.onProgress(0.2, 39.7, 3.0);
  // A stop that a mode's answer replaces 0.3 s later: the vehicle only braked to 2.4 m/s.
  b.onDecision(decision(0.25, arbiter_status_t::OUTCOME_STOPPING, 3, 0, "no usable answer"));
  b.onProgress(0.3, 39.4, 2.8);
  b.onProgress(0.4, 39.1, 2.6);
  b.onProgress(0.5, 38.9, 2.4);
  b.onDecision(decision(0.55, arbiter_status_t::OUTCOME_COMMITTED, 4, 1 << kEam, "committed"));
  b.onProgress(0.6, 38.6, 2.6);  // after the commit: not part of the stop
  // A second stop that brakes to rest and holds until the flight ends.
  b.onDecision(decision(1.0, arbiter_status_t::OUTCOME_STOPPING, 3, 0, "no usable answer"));
  b.onProgress(1.5, 37.5, 1.2);
  b.onProgress(2.5, 37.2, 0.05);
  b.onProgress(3.0, 37.2, 0.0);
  const FlightCensus c = b.finish(4.0);
  ASSERT_EQ(c.stops.size(), 2u);
  EXPECT_DOUBLE_EQ(c.stops[0].held_s, 0.3);
  // The sample before the stop (3.0 m/s) and those while it held; not the one after the commit.
  EXPECT_DOUBLE_EQ(c.stops[0].lowest_speed_mps, 2.4);
  EXPECT_FALSE(c.stops[0].reachedRest());
  EXPECT_DOUBLE_EQ(c.stops[1].held_s, 3.0);
  EXPECT_DOUBLE_EQ(c.stops[1].lowest_speed_mps, 0.0);
  EXPECT_TRUE(c.stops[1].reachedRest());
  // A stop that another stop follows ends there.
  StopCensusBuilder twice;
  twice.onProgress(0.0, 40.0, 1.0);
  twice.onDecision(decision(0.5, arbiter_status_t::OUTCOME_STOPPING, 3, 0, "no usable answer"));
  twice.onDecision(decision(0.7, arbiter_status_t::OUTCOME_STOPPING, 3, 0, "LOCAL_MAP is stale"));
  const FlightCensus t = twice.finish(1.0);
  ASSERT_EQ(t.stops.size(), 2u);
  EXPECT_NEAR(t.stops[0].held_s, 0.2, 1e-12);
  EXPECT_NEAR(t.stops[1].held_s, 0.3, 1e-12);
  EXPECT_DOUBLE_EQ(t.stops[1].lowest_speed_mps, 1.0);
}

TEST(StopCensus, LongestNoProgressNeedsMoreThanATenthOfAMetre) {
  StopCensusBuilder b;
  b.onProgress(0.0, 40.0, 3.0);
  b.onProgress(1.0, 37.0, 3.0);   // progress: 1 s without
  b.onProgress(2.0, 36.95, 3.0);  // less than 0.1 m: no progress
  b.onProgress(3.0, 36.99, 3.0);  // backwards
  b.onProgress(4.5, 36.95, 3.0);
  b.onProgress(5.0, 36.85, 3.0);  // progress after 4 s (from t = 1)
  b.onProgress(6.0, 30.0, 3.0);
  FlightCensus c = b.finish(6.5);
  EXPECT_DOUBLE_EQ(c.longest_no_progress_s, 4.0);
  EXPECT_DOUBLE_EQ(c.longest_no_progress_from_s, 1.0);
  // A flight that ends without progress (timeout): the open stretch counts.
  c = b.finish(12.0);
  EXPECT_DOUBLE_EQ(c.longest_no_progress_s, 6.0);
  EXPECT_DOUBLE_EQ(c.longest_no_progress_from_s, 6.0);
}

}  // namespace
}  // namespace mmh
