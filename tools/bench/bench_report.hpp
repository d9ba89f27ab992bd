// Aggregates mission-benchmark flights into the paper's tables (Table I: time, distance, energy
// as avg/std/max/min; Table II: iterations and cost per iteration), success rates and the
// paper's figures beside ours, written as Markdown.
#pragma once

#include <string>
#include <vector>

#include "flight_spec.hpp"

namespace mmh::bench {

struct Stat {
  int n = 0;
  double avg = 0, std = 0, max = 0, min = 0;
};
// Over finite values only.
Stat statOf(const std::vector<double>& values);

// The paper's MMH figures and the best figure of its Table I, for a density (NaN if unknown).
struct PaperFigures {
  double time_mmh, time_best, distance_mmh, energy_mmh, iterations_mmh, cost_ms_mmh;
};
PaperFigures paperFigures(double density);

// The census of stops and stalls per density and method (all flights, failed ones included):
// stops, their most frequent causes and failed modes, the longest run of planning calls without
// a commit and the longest time without progress toward the goal. Part of summaryMarkdown.
std::string stopCensusMarkdown(const std::vector<FlightResult>& results);

// Where the time goes per density and method (successful flights): the mean time flown on each
// mode and the time lost on it against v_max. Part of summaryMarkdown.
std::string timeByModeMarkdown(const std::vector<FlightResult>& results);

// Where the energy goes per density and method (successful flights): the mean integral of
// |jerk|^2 flown on each mode. Part of summaryMarkdown.
std::string energyByModeMarkdown(const std::vector<FlightResult>& results);

std::string summaryMarkdown(const std::vector<FlightResult>& results, const std::string& command,
                            double wall_time_s);

}  // namespace mmh::bench
