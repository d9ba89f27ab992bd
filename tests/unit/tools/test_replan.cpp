// mmh-replan's summary: failure kinds without their numbers, the counts of fixed and broken
// requests, and the speed and energy of the answers (the planning itself is covered by the
// integration test on a recorded flight).
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "replan.hpp"

namespace {

mmh::ReplanOutcome outcome(bool logged_ok, bool ok, const std::string& detail = "",
                           double ms = 1.0) {
  mmh::ReplanOutcome o;
  o.logged_answer = true;
  o.logged_ok = logged_ok;
  o.logged_detail = logged_ok ? "" : "then";
  o.ok = ok;
  o.detail = detail;
  o.compute_ms = ms;
  return o;
}

TEST(Replan, FailureKindTakesOutNumbersAndStepTimes) {
  EXPECT_EQ(mmh::failureKind("optimizer: still in collision after 12 rounds"),
            "optimizer: still in collision after # rounds");
  EXPECT_EQ(mmh::failureKind("verification: max acceleration 5.416 m/s^2 exceeds 2 [A* 0.17 ms, "
                             "corridor 0.28 ms (5 polytopes)]"),
            "verification: max acceleration # m/s^# exceeds #");
  EXPECT_EQ(mmh::failureKind("enters the inflated obstacles at t=-1.5e-3 s"),
            "enters the inflated obstacles at t=-# s");
  EXPECT_EQ(mmh::failureKind("no map"), "no map");
  EXPECT_EQ(mmh::failureKind(""), "");
}

TEST(Replan, SummaryCountsFixedBrokenAndKinds) {
  std::vector<mmh::ReplanOutcome> all = {
      outcome(true, true, "", 1.0),
      outcome(false, true, "", 3.0),                                               // fixed
      outcome(true, false, "optimizer: still in collision after 20 rounds", 2.0),  // broken
      outcome(false, false, "optimizer: still in collision after 12 rounds", 6.0),
  };
  mmh::ReplanOutcome unanswered = outcome(true, false, "no map", 100.0);
  unanswered.logged_answer = false;
  all.push_back(unanswered);
  const mmh::ReplanSummary s = mmh::summarize(all);
  EXPECT_EQ(s.requests, 4);
  EXPECT_EQ(s.unanswered, 1);
  EXPECT_EQ(s.failed_before, 2);
  EXPECT_EQ(s.failed_now, 2);
  EXPECT_EQ(s.fixed, 1);
  EXPECT_EQ(s.broken, 1);
  EXPECT_DOUBLE_EQ(s.mean_compute_ms, 3.0);
  EXPECT_DOUBLE_EQ(s.max_compute_ms, 6.0);
  ASSERT_EQ(s.reasons_now.size(), 1u);
  EXPECT_EQ(s.reasons_now.at("optimizer: still in collision after # rounds"), 2);
  std::ostringstream text;
  mmh::printReplanSummary(s, text);
  EXPECT_NE(text.str().find("failed then 2, now 2: 1 fixed, 1 broken"), std::string::npos)
      << text.str();
}

TEST(Replan, SummaryGivesTheSpeedAndEnergyOfTheAnswersNow) {
  mmh::ReplanOutcome slow = outcome(true, true);
  slow.length_m = 10.0;
  slow.duration_s = 8.0;
  slow.jerk_energy = 30.0;
  mmh::ReplanOutcome fast = outcome(false, true);
  fast.length_m = 14.0;
  fast.duration_s = 4.0;
  fast.jerk_energy = 10.0;
  // A failure now adds neither length, duration nor energy (its trajectory is empty).
  mmh::ReplanOutcome failed = outcome(true, false, "no map");
  failed.length_m = 99.0;
  failed.duration_s = 99.0;
  failed.jerk_energy = 99.0;
  const mmh::ReplanSummary s = mmh::summarize({slow, fast, failed});
  EXPECT_DOUBLE_EQ(s.answered_length_m, 24.0);
  EXPECT_DOUBLE_EQ(s.answered_duration_s, 12.0);
  EXPECT_DOUBLE_EQ(s.mean_speed_mps, 2.0);  // total length over total duration
  EXPECT_DOUBLE_EQ(s.mean_jerk_energy, 20.0);
  std::ostringstream text;
  mmh::printReplanSummary(s, text);
  EXPECT_NE(text.str().find("answers now: 24.0 m in 12.0 s (mean speed 2.00 m/s), mean energy "
                            "20.0 m^2/s^5"),
            std::string::npos)
      << text.str();
}

TEST(Replan, NoAnswerNowPrintsNoAnswerLine) {
  const mmh::ReplanSummary s = mmh::summarize({outcome(true, false, "no map")});
  EXPECT_DOUBLE_EQ(s.mean_speed_mps, 0.0);
  std::ostringstream text;
  mmh::printReplanSummary(s, text);
  EXPECT_EQ(text.str().find("answers now"), std::string::npos) << text.str();
}

TEST(Replan, AnEmptyLogSummarisesToZeros) {
  const mmh::ReplanSummary s = mmh::summarize({});
  EXPECT_EQ(s.requests, 0);
  EXPECT_EQ(s.failed_now, 0);
  EXPECT_DOUBLE_EQ(s.mean_compute_ms, 0.0);
}

}  // namespace

namespace {

// Along +x from the origin: 1 m/s and 2 m/s^2 for 0.12 s.
mmh::Trajectory accelerating() {
  mmh::Piece p;
  p.duration = 0.12;
  p.coeffs.col(1) = Eigen::Vector3d(1.0, 0.0, 0.0);
  p.coeffs.col(2) = Eigen::Vector3d(1.0, 0.0, 0.0);
  return mmh::Trajectory({p});
}

}  // namespace

TEST(Replan, SamplesATrajectoryEveryStepAndAtItsEnd) {
  std::ostringstream out;
  mmh::printTrajectorySamples(accelerating(), 0.05, out);
  std::istringstream lines(out.str());
  std::string header;
  std::getline(lines, header);
  EXPECT_NE(header.find("speed"), std::string::npos);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line);
    std::vector<double> row;
    for (double v; fields >> v;) row.push_back(v);
    rows.push_back(row);
  }
  ASSERT_EQ(rows.size(), 4u);  // 0, 0.05, 0.10 and the end, 0.12
  const double times[] = {0.0, 0.05, 0.10, 0.12};
  for (size_t i = 0; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), 7u);
    const double t = times[i];
    EXPECT_NEAR(rows[i][0], t, 1e-9);
    EXPECT_NEAR(rows[i][1], t + t * t, 0.005);      // x
    EXPECT_NEAR(rows[i][4], 1.0 + 2.0 * t, 0.005);  // speed
    EXPECT_NEAR(rows[i][5], 2.0, 0.005);            // acceleration
    EXPECT_NEAR(rows[i][6], 0.0, 0.005);            // jerk
  }
}

TEST(Replan, SamplesOfAnEmptyTrajectoryAreOnlyTheHeader) {
  std::ostringstream out;
  mmh::printTrajectorySamples(mmh::Trajectory(), 0.05, out);
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1);
}
