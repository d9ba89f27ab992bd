// mmh-bench-compare: flights are paired by their identity, not their order; the mean change and
// its bootstrap interval have known answers for identical and shifted runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "bench_compare.hpp"

namespace mmh::bench {
namespace {

FlightResult flight(const std::string& method, double density, int64_t map_seed, int64_t noise_seed,
                    double time_ratio, int stops = 0, bool success = true) {
  FlightResult r;
  r.spec.method = method;
  r.spec.density = density;
  r.spec.map_seed = map_seed;
  r.spec.noise_seed = noise_seed;
  r.success = r.reached = success;
  r.time_bound_s = 10.0;
  r.time_ratio = time_ratio;
  r.flight_time_s = time_ratio * r.time_bound_s;
  r.stops = stops;
  r.energy = 100.0 * time_ratio;
  r.iterations = 10;
  return r;
}

std::vector<FlightResult> run(double shift) {
  std::vector<FlightResult> flights;
  const double ratios[] = {1.0, 1.2, 1.1, 1.5, 1.05, 1.3};
  for (int i = 0; i < 6; ++i)
    flights.push_back(flight("mmh", 0.2, 1300 + i / 3, i, ratios[i] + shift));
  return flights;
}

TEST(BenchCompare, IdenticalRunsChangeNothing) {
  const Comparison c = comparePaired(run(0.0), run(0.0));
  ASSERT_EQ(c.groups.size(), 1u);
  const PairedGroup& g = c.groups[0];
  EXPECT_EQ(g.pairs, 6);
  EXPECT_EQ(g.both_succeeded, 6);
  EXPECT_DOUBLE_EQ(g.ratio_change, 0.0);
  EXPECT_DOUBLE_EQ(g.ratio_change_interval.low, 0.0);
  EXPECT_DOUBLE_EQ(g.ratio_change_interval.high, 0.0);
  EXPECT_EQ(g.faster, 0);
  EXPECT_EQ(g.slower, 0);
  EXPECT_EQ(c.only_base, 0);
  EXPECT_EQ(c.only_cand, 0);
}

TEST(BenchCompare, AConstantShiftIsFoundExactlyWhateverTheOrder) {
  std::vector<FlightResult> cand = run(-0.05);
  std::reverse(cand.begin(), cand.end());
  const Comparison c = comparePaired(run(0.0), cand);
  ASSERT_EQ(c.groups.size(), 1u);
  const PairedGroup& g = c.groups[0];
  EXPECT_NEAR(g.ratio_change, -0.05, 1e-12);
  EXPECT_NEAR(g.ratio_change_interval.low, -0.05, 1e-12);
  EXPECT_NEAR(g.ratio_change_interval.high, -0.05, 1e-12);
  EXPECT_NEAR(g.ratio_base - g.ratio_cand, 0.05, 1e-12);
  EXPECT_EQ(g.faster, 6);  // every flight more than 1 % faster
}

TEST(BenchCompare, UnpairedAndFailedFlightsAreCountedNotAveraged) {
  std::vector<FlightResult> base = run(0.0), cand = run(0.0);
  cand[0] = flight("mmh", 0.2, 1300, 0, 9.0, 3, /*success=*/false);  // failed in the candidate
  cand.pop_back();                                                   // never flown there
  base.push_back(flight("som", 0.2, 1300, 0, 1.4));                  // another method, alone
  const Comparison c = comparePaired(base, cand);
  ASSERT_EQ(c.groups.size(), 1u);
  const PairedGroup& g = c.groups[0];
  EXPECT_EQ(g.pairs, 5);
  EXPECT_EQ(g.success_base, 5);
  EXPECT_EQ(g.success_cand, 4);
  EXPECT_EQ(g.stops_cand, 3);
  EXPECT_EQ(g.both_succeeded, 4);
  EXPECT_DOUBLE_EQ(g.ratio_change, 0.0);  // the failed flight's 9.0 is not in the mean
  EXPECT_EQ(c.only_base, 2);
  EXPECT_EQ(c.only_cand, 0);
}

TEST(BenchCompare, GroupsSplitByMethodAndDensity) {
  std::vector<FlightResult> base = {flight("mmh", 0.1, 1, 1, 1.0), flight("mmh", 0.2, 1, 1, 1.2),
                                    flight("ego", 0.2, 1, 1, 1.4)};
  const Comparison c = comparePaired(base, base);
  ASSERT_EQ(c.groups.size(), 3u);
  for (const PairedGroup& g : c.groups) EXPECT_EQ(g.pairs, 1);
}

TEST(BenchCompare, BootstrapIntervalHoldsTheMeanAndIsReproducible) {
  const std::vector<double> x = {-0.3, 0.1, 0.05, -0.1, 0.2, -0.02, 0.4, -0.25};
  const Interval a = bootstrapMeanInterval(x, 0.95, 5000, 7);
  const Interval b = bootstrapMeanInterval(x, 0.95, 5000, 7);
  double mean = 0;
  for (double v : x) mean += v / x.size();
  EXPECT_LT(a.low, mean);
  EXPECT_GT(a.high, mean);
  EXPECT_GE(a.low, *std::min_element(x.begin(), x.end()));
  EXPECT_LE(a.high, *std::max_element(x.begin(), x.end()));
  EXPECT_EQ(a.low, b.low);
  EXPECT_EQ(a.high, b.high);
  // A wider confidence gives a wider interval.
  const Interval wide = bootstrapMeanInterval(x, 0.99, 5000, 7);
  EXPECT_LE(wide.low, a.low);
  EXPECT_GE(wide.high, a.high);
  EXPECT_TRUE(std::isnan(bootstrapMeanInterval({}, 0.95, 100, 1).low));
}

TEST(BenchCompare, MarkdownNamesTheRunsAndTheGroups) {
  const std::string md = comparisonMarkdown(comparePaired(run(0.0), run(0.1)), "out/a", "out/b");
  EXPECT_NE(md.find("`out/a`"), std::string::npos);
  EXPECT_NE(md.find("| forest | 0.20 | mmh | 6 |"), std::string::npos);
  EXPECT_NE(md.find("+0.100"), std::string::npos);
}

}  // namespace
}  // namespace mmh::bench
