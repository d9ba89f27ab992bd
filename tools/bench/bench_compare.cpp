#include "bench_compare.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <tuple>

#include "bench_report.hpp"

namespace mmh::bench {
namespace {

// Everything that makes two flights the same flight, except the configuration under test.
std::string pairKey(const FlightSpec& s) {
  std::ostringstream k;
  k << std::setprecision(6) << s.method << '|' << s.world << '|' << s.density << '|' << s.sensor
    << '|' << s.map_seed << '|' << s.noise_seed << '|' << s.start.transpose() << '|'
    << s.goal.transpose() << '|' << s.size_m.transpose();
  return k.str();
}

// The mean over finite values, NaN for none (the benchmark tables' own statistic).
double mean(const std::vector<double>& v) {
  return statOf(v).avg;
}

// The relative change of time above which a flight counts as faster or slower.
constexpr double kTimeChangeThreshold = 0.01;

}  // namespace

Interval bootstrapMeanInterval(const std::vector<double>& values, double confidence, int resamples,
                               uint64_t seed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (values.empty() || resamples < 1) return {nan, nan};
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<size_t> pick(0, values.size() - 1);
  std::vector<double> means(static_cast<size_t>(resamples));
  for (double& m : means) {
    double sum = 0;
    for (size_t i = 0; i < values.size(); ++i) sum += values[pick(rng)];
    m = sum / static_cast<double>(values.size());
  }
  std::sort(means.begin(), means.end());
  const double tail = 0.5 * (1.0 - confidence);
  const auto at = [&](double q) {
    const double pos = q * static_cast<double>(means.size() - 1);
    return means[static_cast<size_t>(std::lround(pos))];
  };
  return {at(tail), at(1.0 - tail)};
}

Comparison comparePaired(const std::vector<FlightResult>& base,
                         const std::vector<FlightResult>& cand, double confidence, int resamples,
                         uint64_t seed) {
  Comparison out;
  std::map<std::string, const FlightResult*> cand_by_key;
  for (const FlightResult& c : cand) cand_by_key[pairKey(c.spec)] = &c;

  using GroupKey = std::tuple<std::string, double, std::string>;  // world, density, method
  struct Samples {
    PairedGroup group;
    std::vector<double> base_ratio, cand_ratio, change, base_energy, cand_energy, base_it, cand_it;
  };
  std::map<GroupKey, Samples> groups;
  std::set<std::string> matched;
  for (const FlightResult& b : base) {
    const std::string key = pairKey(b.spec);
    const auto it = cand_by_key.find(key);
    if (it == cand_by_key.end() || !matched.insert(key).second) {
      ++out.only_base;
      continue;
    }
    const FlightResult& c = *it->second;
    Samples& s = groups[{b.spec.world, b.spec.density, b.spec.method}];
    PairedGroup& g = s.group;
    g.method = b.spec.method;
    g.world = b.spec.world;
    g.density = b.spec.density;
    ++g.pairs;
    g.success_base += b.success;
    g.success_cand += c.success;
    g.collided_base += b.collided;
    g.collided_cand += c.collided;
    g.stops_base += b.stops;
    g.stops_cand += c.stops;
    if (!b.success || !c.success) continue;
    ++g.both_succeeded;
    s.base_ratio.push_back(b.time_ratio);
    s.cand_ratio.push_back(c.time_ratio);
    s.change.push_back(c.time_ratio - b.time_ratio);
    s.base_energy.push_back(b.energy);
    s.cand_energy.push_back(c.energy);
    s.base_it.push_back(b.iterations);
    s.cand_it.push_back(c.iterations);
    const double relative = c.flight_time_s / b.flight_time_s - 1.0;
    if (relative < -kTimeChangeThreshold) ++g.faster;
    if (relative > kTimeChangeThreshold) ++g.slower;
  }
  out.only_cand = static_cast<int>(cand.size()) - static_cast<int>(matched.size());
  for (auto& [key, s] : groups) {
    PairedGroup& g = s.group;
    g.ratio_base = mean(s.base_ratio);
    g.ratio_cand = mean(s.cand_ratio);
    g.ratio_change = mean(s.change);
    g.ratio_change_interval = bootstrapMeanInterval(s.change, confidence, resamples, seed);
    g.energy_base = mean(s.base_energy);
    g.energy_cand = mean(s.cand_energy);
    g.iterations_base = mean(s.base_it);
    g.iterations_cand = mean(s.cand_it);
    out.groups.push_back(g);
  }
  return out;
}

std::string comparisonMarkdown(const Comparison& comparison, const std::string& base_label,
                               const std::string& cand_label, double confidence) {
  std::ostringstream md;
  md << std::fixed;
  md << "# Paired comparison\n\nBaseline: `" << base_label << "`  \nCandidate: `" << cand_label
     << "`\n\nFlights matched by method, world, density, forest and noise seed. Change = "
        "candidate − baseline of time / bound, per flight, averaged over the flights both "
        "reached; the interval is a "
     << std::setprecision(0) << confidence * 100
     << " % bootstrap interval of that mean. An interval that contains 0 does not tell the two "
        "apart. Faster / slower: flights whose time changed by more than 1 %.\n\n";
  md << "| world | density | method | pairs | success | collided | stops | time / bound | change "
        "| interval | faster / slower | energy | iterations |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const PairedGroup& g : comparison.groups) {
    md << "| " << g.world << " | " << std::setprecision(2) << g.density << " | " << g.method
       << " | " << g.pairs << " | " << g.success_base << " → " << g.success_cand << " | "
       << g.collided_base << " → " << g.collided_cand << " | " << g.stops_base << " → "
       << g.stops_cand << " | " << std::setprecision(3) << g.ratio_base << " → " << g.ratio_cand
       << " | " << std::showpos << g.ratio_change << " | [" << g.ratio_change_interval.low << ", "
       << g.ratio_change_interval.high << "]" << std::noshowpos << " | " << g.faster << " / "
       << g.slower << " | " << std::setprecision(1) << g.energy_base << " → " << g.energy_cand
       << " | " << g.iterations_base << " → " << g.iterations_cand << " |\n";
  }
  if (comparison.only_base || comparison.only_cand) {
    md << "\nLeft out, without a partner: " << comparison.only_base << " flights of the baseline, "
       << comparison.only_cand << " of the candidate.\n";
  }
  return md.str();
}

}  // namespace mmh::bench
