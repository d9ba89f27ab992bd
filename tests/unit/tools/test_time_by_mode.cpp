// Where a flight's time goes: time and loss against v_max per mode from the flown path, their
// sum, and their round trip through results.json (old records without them read as zeros).
#include <gtest/gtest.h>

#include "bench_report.hpp"
#include "flight_spec.hpp"
#include "time_by_mode.hpp"

namespace mmh {
namespace {

PathSample sample(double t, double speed, int mode, double energy = 0.0) {
  PathSample s;
  s.t = t;
  s.speed = speed;
  s.mode = mode;
  s.energy = energy;
  return s;
}

TEST(TimeByMode, EachSampleHoldsItsModeAndSpeedUntilTheNext) {
  // 1 s before the first plan at rest, 2 s of FPM at full speed, 1 s of EAM at half speed,
  // 0.5 s of stop at a quarter; the last sample only closes the path.
  const std::vector<PathSample> path = {sample(0.0, 0.0, 0), sample(1.0, 3.0, 1),
                                        sample(3.0, 1.5, 3), sample(4.0, 0.75, 4),
                                        sample(4.5, 0.0, 4)};
  const TimeByMode t = timeByMode(path, 3.0);
  EXPECT_DOUBLE_EQ(t.time_s[0], 1.0);
  EXPECT_DOUBLE_EQ(t.time_s[1], 2.0);
  EXPECT_DOUBLE_EQ(t.time_s[2], 0.0);
  EXPECT_DOUBLE_EQ(t.time_s[3], 1.0);
  EXPECT_DOUBLE_EQ(t.time_s[4], 0.5);
  EXPECT_DOUBLE_EQ(t.lost_s[0], 1.0);    // at rest: all lost
  EXPECT_DOUBLE_EQ(t.lost_s[1], 0.0);    // at v_max: nothing lost
  EXPECT_DOUBLE_EQ(t.lost_s[3], 0.5);    // half speed for 1 s
  EXPECT_DOUBLE_EQ(t.lost_s[4], 0.375);  // a quarter for 0.5 s
}

TEST(TimeByMode, TheEnergyOfAStepCountsForTheModeFlownAtItsEnd) {
  // Cumulative energy 0 at the start, 0.5 after the step into FPM, 2 after FPM, 12 after the step
  // into EAM and EAM, 13 after the stop: a new trajectory's jerk comes right after its commit.
  const std::vector<PathSample> path = {sample(0.0, 0.0, 0, 0.0), sample(1.0, 3.0, 1, 0.5),
                                        sample(3.0, 1.5, 1, 2.0), sample(4.0, 0.75, 3, 12.0),
                                        sample(4.5, 0.0, 4, 13.0)};
  const TimeByMode t = timeByMode(path, 3.0);
  EXPECT_DOUBLE_EQ(t.energy[0], 0.0);  // nothing flown before the first plan
  EXPECT_DOUBLE_EQ(t.energy[1], 2.0);
  EXPECT_DOUBLE_EQ(t.energy[2], 0.0);
  EXPECT_DOUBLE_EQ(t.energy[3], 10.0);
  EXPECT_DOUBLE_EQ(t.energy[4], 1.0);
  double all = 0;
  for (double e : t.energy) all += e;
  EXPECT_DOUBLE_EQ(all, path.back().energy);  // the modes add up to the flight's energy
}

TEST(TimeByMode, LossAddsUpToTimeMinusDistanceOverVmax) {
  std::vector<PathSample> path;
  double distance = 0;
  for (int i = 0; i <= 100; ++i) {
    const double speed = 3.0 * (0.5 + 0.5 * std::sin(0.1 * i) * std::sin(0.1 * i));
    path.push_back(sample(0.1 * i, speed, 1 + i % 3));
    if (i < 100) distance += 0.1 * speed;
  }
  const TimeByMode t = timeByMode(path, 3.0);
  double time = 0, lost = 0;
  for (int m = 0; m < kModeSlots; ++m) {
    time += t.time_s[m];
    lost += t.lost_s[m];
  }
  EXPECT_NEAR(time, 10.0, 1e-9);
  EXPECT_NEAR(lost, 10.0 - distance / 3.0, 1e-9);
}

TEST(TimeByMode, OddInputCountsAsNoneOrNothing) {
  const std::vector<PathSample> path = {sample(0.0, 4.0, 9), sample(1.0, 1.0, 2),
                                        sample(1.0, 1.0, 2)};  // faster than v_max, a repeat
  const TimeByMode t = timeByMode(path, 3.0);
  EXPECT_DOUBLE_EQ(t.time_s[0], 1.0);  // unknown mode 9
  EXPECT_DOUBLE_EQ(t.lost_s[0], 0.0);  // above v_max loses nothing (never negative)
  EXPECT_DOUBLE_EQ(t.time_s[2], 0.0);  // zero-length step
  EXPECT_DOUBLE_EQ(timeByMode(path, 0.0).time_s[0], 0.0);
}

TEST(TimeByMode, RoundTripsThroughResultsJsonAndReadsOldRecords) {
  bench::FlightResult r;
  r.success = true;
  r.time_by_mode.time_s = {0.5, 4.0, 6.0, 3.0, 0.2};
  r.time_by_mode.lost_s = {0.5, 0.1, 1.5, 0.9, 0.1};
  r.time_by_mode.energy = {0.0, 3.5, 40.0, 20.5, 1.0};
  nlohmann::json j = bench::toJson(r);
  EXPECT_DOUBLE_EQ(j.at("time_by_mode_s").at("som").get<double>(), 6.0);
  EXPECT_DOUBLE_EQ(j.at("time_lost_by_mode_s").at("eam").get<double>(), 0.9);
  const bench::FlightResult back = bench::fromJson(j);
  EXPECT_EQ(back.time_by_mode.time_s, r.time_by_mode.time_s);
  EXPECT_EQ(back.time_by_mode.lost_s, r.time_by_mode.lost_s);
  EXPECT_EQ(back.time_by_mode.energy, r.time_by_mode.energy);
  j.erase("time_by_mode_s");
  j.erase("time_lost_by_mode_s");
  j.erase("energy_by_mode");
  EXPECT_DOUBLE_EQ(bench::fromJson(j).time_by_mode.time_s[2], 0.0);
  EXPECT_DOUBLE_EQ(bench::fromJson(j).time_by_mode.energy[2], 0.0);
}

TEST(TimeByMode, SummaryTableHasOneRowPerDensityAndMethod) {
  bench::FlightResult r;
  r.spec.method = "mmh";
  r.spec.density = 0.2;
  r.success = true;
  r.time_by_mode.time_s = {0.5, 4.0, 6.0, 3.0, 0.2};
  r.time_by_mode.lost_s = {0.5, 0.1, 1.5, 0.9, 0.1};
  const std::string md = bench::timeByModeMarkdown({r, r});
  EXPECT_NE(md.find("## Where the time goes"), std::string::npos);
  EXPECT_NE(md.find("| 0.20 | mmh | 2 | 4.00 (0.10) | 6.00 (1.50) | 3.00 (0.90) | 0.20 (0.10) | "
                    "0.50 (0.50) | 3.10 |"),
            std::string::npos)
      << md;
}

TEST(TimeByMode, EnergySummaryTableAddsTheModesUp) {
  bench::FlightResult r;
  r.spec.method = "som";
  r.spec.density = 0.1;
  r.success = true;
  r.time_by_mode.energy = {0.0, 3.5, 40.0, 20.5, 1.0};
  bench::FlightResult failed = r;
  failed.success = false;  // only successful flights count, as in the other tables
  failed.time_by_mode.energy = {0.0, 100.0, 100.0, 100.0, 100.0};
  const std::string md = bench::energyByModeMarkdown({r, r, failed});
  EXPECT_NE(md.find("## Where the energy goes"), std::string::npos);
  EXPECT_NE(md.find("| 0.10 | som | 2 | 3.5 | 40.0 | 20.5 | 1.0 | 65.0 |"), std::string::npos)
      << md;
}

}  // namespace
}  // namespace mmh
