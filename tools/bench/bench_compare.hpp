// Paired comparison of two mission-benchmark runs over the same flights (a baseline and a
// candidate configuration or build): flights are matched by method, world, density, forest and
// noise seed, and each group reports the mean change of time / bound with a bootstrap confidence
// interval, so a change of a few per cent can be told from the chaos of single flights.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "flight_spec.hpp"

namespace mmh::bench {

// Percentile bootstrap of the mean: `resamples` resamples with replacement, drawn from a
// generator seeded with `seed` (the same inputs give the same interval). An empty sample gives
// NaN bounds; one value gives that value for both.
struct Interval {
  double low, high;
};
Interval bootstrapMeanInterval(const std::vector<double>& values, double confidence, int resamples,
                               uint64_t seed);

// One method at one density of one world, over the flights both runs flew.
struct PairedGroup {
  std::string method, world;
  double density = 0;
  int pairs = 0;  // flights present in both runs
  int success_base = 0, success_cand = 0;
  int collided_base = 0, collided_cand = 0;
  int stops_base = 0, stops_cand = 0;
  int both_succeeded = 0;                 // the flights the means below are over
  double ratio_base = 0, ratio_cand = 0;  // mean time / bound
  double ratio_change = 0;                // mean of (candidate - baseline), per flight
  Interval ratio_change_interval{0, 0};   // its bootstrap interval
  int faster = 0, slower = 0;             // flights whose time changed by more than 1 %
  double energy_base = 0, energy_cand = 0;
  double iterations_base = 0, iterations_cand = 0;
};

struct Comparison {
  std::vector<PairedGroup> groups;   // ordered by world, density, method
  int only_base = 0, only_cand = 0;  // flights without a partner (left out)
};

Comparison comparePaired(const std::vector<FlightResult>& base,
                         const std::vector<FlightResult>& cand, double confidence = 0.95,
                         int resamples = 10000, uint64_t seed = 1);

std::string comparisonMarkdown(const Comparison& comparison, const std::string& base_label,
                               const std::string& cand_label, double confidence = 0.95);

}  // namespace mmh::bench
