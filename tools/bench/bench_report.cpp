#include "bench_report.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

namespace mmh::bench {
namespace {

std::string fmt(double v, int digits = 2) {
  if (!std::isfinite(v)) return "–";
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

std::string densityLabel(double d) {
  return d < 0 ? "own world" : fmt(d, 2);
}

// "a ×3, b ×1": the counts, most frequent first (ties by name), at most `limit` of them.
std::string topCounts(const std::map<std::string, int>& counts, size_t limit) {
  std::vector<std::pair<std::string, int>> sorted(counts.begin(), counts.end());
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  std::string out;
  for (size_t i = 0; i < sorted.size() && i < limit; ++i) {
    if (i) out += ", ";
    out += sorted[i].first + " ×" + std::to_string(sorted[i].second);
  }
  return out.empty() ? "–" : out;
}

struct Groups {
  std::set<double> densities;
  std::vector<std::string> methods;
};

Groups groupsOf(const std::vector<FlightResult>& results) {
  Groups g;
  for (const FlightResult& r : results) {
    g.densities.insert(r.spec.density);
    if (std::find(g.methods.begin(), g.methods.end(), r.spec.method) == g.methods.end())
      g.methods.push_back(r.spec.method);
  }
  return g;
}

// The flights of one density and method, in their order.
std::vector<const FlightResult*> flightsOf(const std::vector<FlightResult>& results, double density,
                                           const std::string& method) {
  std::vector<const FlightResult*> out;
  for (const FlightResult& r : results)
    if (r.spec.density == density && r.spec.method == method) out.push_back(&r);
  return out;
}

using ModeSlots = std::array<double, kModeSlots>;

// The mean per successful flight of one per-mode field of TimeByMode; 0 successful flights: zeros.
ModeSlots meanOfSuccessful(const std::vector<const FlightResult*>& flights,
                           ModeSlots TimeByMode::*field, int* successful) {
  ModeSlots mean{};
  *successful = 0;
  for (const FlightResult* r : flights) {
    if (!r->success) continue;
    ++*successful;
    for (int i = 0; i < kModeSlots; ++i) mean[i] += (r->time_by_mode.*field)[i];
  }
  for (double& v : mean) v /= std::max(1, *successful);
  return mean;
}

}  // namespace

std::string stopCensusMarkdown(const std::vector<FlightResult>& results) {
  const Groups g = groupsOf(results);
  std::ostringstream md;
  md << "## Stops and stalls\n\n"
        "All flights. A stop is an arbiter decision with outcome stopping; its cause comes from "
        "the decision's text, the failed modes from the failed decision just before it. Calls "
        "without commit: planning calls in a row whose rounds all ended without a commit. No "
        "progress: the distance to the goal did not shrink by "
     << fmt(kProgressStepM, 1) << " m. To rest: stops during which the vehicle slowed to "
     << fmt(kRestSpeedMps, 1)
     << " m/s or less (the others only braked until a mode's answer replaced them). Held: "
        "from the stop to the next commit, mean over the stops. Per-stop detail in "
        "results.json (`stop_events`).\n\n"
        "| density | method | flights | stops | to rest | held (s) | stops / flight | causes | "
        "failed modes at the stops | max calls w/o commit | longest no progress (s) | mean "
        "longest no progress (s) |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (double d : g.densities) {
    for (const std::string& m : g.methods) {
      std::map<std::string, int> causes, failed_modes;
      int flights = 0, stops = 0, to_rest = 0, max_calls = 0;
      std::vector<double> no_progress, held;
      for (const FlightResult& r : results) {
        if (r.spec.density != d || r.spec.method != m || !r.error.empty()) continue;
        ++flights;
        for (const StopRecord& s : r.census.stops) {
          ++stops;
          if (s.reachedRest()) ++to_rest;
          if (std::isfinite(s.held_s)) held.push_back(s.held_s);
          ++causes[s.cause];
          for (const ModeFailure& f : s.failed_modes) ++failed_modes[f.mode + " " + f.reason];
        }
        max_calls = std::max(max_calls, r.census.max_calls_without_commit);
        no_progress.push_back(r.census.longest_no_progress_s);
      }
      if (flights == 0) continue;
      const Stat np = statOf(no_progress);
      md << "| " << densityLabel(d) << " | " << m << " | " << flights << " | " << stops << " | "
         << to_rest << " | " << fmt(held.empty() ? NAN : statOf(held).avg) << " | "
         << fmt(double(stops) / flights) << " | " << topCounts(causes, 4) << " | "
         << topCounts(failed_modes, 4) << " | " << max_calls << " | " << fmt(np.max, 1) << " | "
         << fmt(np.avg, 1) << " |\n";
    }
  }
  return md.str();
}

std::string energyByModeMarkdown(const std::vector<FlightResult>& results) {
  const Groups g = groupsOf(results);
  std::ostringstream md;
  md << "## Where the energy goes\n\n"
        "Successful flights, mean per flight: the energy (integral of |jerk|^2, m^2/s^5) flown on "
        "each mode's trajectory; the columns add up to the flight's energy. Per flight in "
        "results.json (`energy_by_mode`).\n\n"
        "| density | method | flights | FPM | SOM | EAM | stop | all |\n"
        "|---|---|---|---|---|---|---|---|\n";
  const int order[] = {1, 2, 3, 4};
  for (double d : g.densities) {
    for (const std::string& m : g.methods) {
      int flights = 0;
      const ModeSlots energy =
          meanOfSuccessful(flightsOf(results, d, m), &TimeByMode::energy, &flights);
      if (flights == 0) continue;
      double all = 0;
      for (double e : energy) all += e;
      md << "| " << densityLabel(d) << " | " << m << " | " << flights;
      for (int i : order) md << " | " << fmt(energy[i], 1);
      md << " | " << fmt(all, 1) << " |\n";
    }
  }
  return md.str();
}

std::string timeByModeMarkdown(const std::vector<FlightResult>& results) {
  const Groups g = groupsOf(results);
  std::ostringstream md;
  md << "## Where the time goes\n\n"
        "Successful flights, mean per flight: the time flown on each mode's trajectory and, in "
        "brackets, the time lost on it against flying at v_max (the integral of 1 - speed / "
        "v_max). The lost times add up to about the flight time minus distance / v_max; they "
        "include the start's acceleration and the braking at the goal (about v_max / a_max "
        "together), which fall on the first and the last mode. Per flight in results.json "
        "(`time_by_mode_s`, `time_lost_by_mode_s`).\n\n"
        "| density | method | flights | FPM (s) | SOM (s) | EAM (s) | stop (s) | before the "
        "first plan (s) | lost in all (s) |\n|---|---|---|---|---|---|---|---|---|\n";
  // Column order: FPM, SOM, EAM, stop, none.
  const int order[kModeSlots] = {1, 2, 3, 4, 0};
  for (double d : g.densities) {
    for (const std::string& m : g.methods) {
      const std::vector<const FlightResult*> flown = flightsOf(results, d, m);
      int flights = 0;
      const ModeSlots time = meanOfSuccessful(flown, &TimeByMode::time_s, &flights);
      const ModeSlots lost = meanOfSuccessful(flown, &TimeByMode::lost_s, &flights);
      if (flights == 0) continue;
      double lost_all = 0;
      md << "| " << densityLabel(d) << " | " << m << " | " << flights;
      for (int i : order) {
        md << " | " << fmt(time[i], 2) << " (" << fmt(lost[i], 2) << ")";
        lost_all += lost[i];
      }
      md << " | " << fmt(lost_all, 2) << " |\n";
    }
  }
  return md.str();
}

Stat statOf(const std::vector<double>& values) {
  Stat s;
  double sum = 0, sq = 0;
  s.max = -INFINITY;
  s.min = INFINITY;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    ++s.n;
    sum += v;
    sq += v * v;
    s.max = std::max(s.max, v);
    s.min = std::min(s.min, v);
  }
  if (s.n == 0) return Stat{0, NAN, NAN, NAN, NAN};
  s.avg = sum / s.n;
  s.std = s.n > 1 ? std::sqrt(std::max(0.0, (sq - s.n * s.avg * s.avg) / (s.n - 1))) : 0.0;
  return s;
}

PaperFigures paperFigures(double d) {
  // docs/benchmark.md (paper Tables I and II).
  if (std::abs(d - 0.0) < 1e-9) return {16.52, 15.39, 39.89, 15.56, 9.0, 0.1};
  if (std::abs(d - 0.05) < 1e-9) return {17.04, 17.04, 40.20, 43.93, 12.7, 0.3};
  if (std::abs(d - 0.1) < 1e-9) return {17.89, 17.89, 40.84, 80.91, 17.5, 0.7};
  if (std::abs(d - 0.2) < 1e-9) return {18.62, 18.62, 41.66, 136.43, 22.5, 0.9};
  return {NAN, NAN, NAN, NAN, NAN, NAN};
}

std::string summaryMarkdown(const std::vector<FlightResult>& results, const std::string& command,
                            double wall_time_s) {
  const Groups groups = groupsOf(results);
  const std::set<double>& densities = groups.densities;
  const std::vector<std::string>& methods = groups.methods;
  // Metrics of successful flights only, as the paper reports them.
  auto collect = [](const std::vector<const FlightResult*>& rs, auto field) {
    std::vector<double> v;
    for (const FlightResult* r : rs)
      if (r->success) v.push_back(field(*r));
    return v;
  };

  std::ostringstream md;
  md << "# Mission benchmark\n\n";
  md << "Command: `" << command << "`  \n";
  md << "Flights: " << results.size() << ", wall time " << fmt(wall_time_s / 60.0, 1)
     << " min. Metrics of successful flights; cost = wall-clock compute time per planning call "
        "on this machine.\n\n";

  md << "## Success\n\n| density | method | flights | success | collided | timeout | stops |\n"
        "|---|---|---|---|---|---|---|\n";
  for (double d : densities) {
    for (const std::string& m : methods) {
      auto rs = flightsOf(results, d, m);
      if (rs.empty()) continue;
      int ok = 0, col = 0, to = 0, stops = 0;
      for (auto* r : rs) {
        ok += r->success;
        col += r->collided;
        to += (!r->reached && !r->collided);
        stops += r->stops;
      }
      md << "| " << densityLabel(d) << " | " << m << " | " << rs.size() << " | "
         << fmt(100.0 * ok / rs.size(), 1) << "% | " << col << " | " << to << " | " << stops
         << " |\n";
    }
  }

  md << "\n## Table I: flight time (s), distance (m), energy (m²/s⁵) — avg / std / max / min\n\n"
        "| density | method | time avg | std | max | min | dist avg | std | max | min | energy "
        "avg | std | max | min | time / bound |\n|---|---|---|---|---|---|---|---|---|---|---|---|"
        "---|---|---|\n";
  for (double d : densities) {
    for (const std::string& m : methods) {
      auto rs = flightsOf(results, d, m);
      if (rs.empty()) continue;
      const Stat t = statOf(collect(rs, [](const FlightResult& r) { return r.flight_time_s; }));
      const Stat l = statOf(collect(rs, [](const FlightResult& r) { return r.distance_m; }));
      const Stat e = statOf(collect(rs, [](const FlightResult& r) { return r.energy; }));
      const Stat q = statOf(collect(rs, [](const FlightResult& r) { return r.time_ratio; }));
      md << "| " << densityLabel(d) << " | " << m << " | " << fmt(t.avg) << " | " << fmt(t.std)
         << " | " << fmt(t.max) << " | " << fmt(t.min) << " | " << fmt(l.avg) << " | " << fmt(l.std)
         << " | " << fmt(l.max) << " | " << fmt(l.min) << " | " << fmt(e.avg) << " | " << fmt(e.std)
         << " | " << fmt(e.max) << " | " << fmt(e.min) << " | " << fmt(q.avg, 3) << " |\n";
    }
    const PaperFigures p = paperFigures(d);
    if (std::isfinite(p.time_mmh)) {
      md << "| " << densityLabel(d) << " | *paper MMH* | " << fmt(p.time_mmh) << " | | | | "
         << fmt(p.distance_mmh) << " | | | | " << fmt(p.energy_mmh) << " | | | | |\n";
      md << "| " << densityLabel(d) << " | *paper best time* | " << fmt(p.time_best)
         << " | | | | | | | | | | | | |\n";
    }
  }

  md << "\n## Table II: planning iterations and computational cost per iteration\n\n"
        "| density | method | iterations avg | FPM | SOM | EAM | cost ms avg | p50 | p99 |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
  for (double d : densities) {
    for (const std::string& m : methods) {
      auto rs = flightsOf(results, d, m);
      if (rs.empty()) continue;
      const Stat it =
          statOf(collect(rs, [](const FlightResult& r) { return double(r.iterations); }));
      const Stat f =
          statOf(collect(rs, [](const FlightResult& r) { return double(r.iterations_fpm); }));
      const Stat s =
          statOf(collect(rs, [](const FlightResult& r) { return double(r.iterations_som); }));
      const Stat e =
          statOf(collect(rs, [](const FlightResult& r) { return double(r.iterations_eam); }));
      // Cost per iteration over all calls of all flights: weight each flight by its calls.
      double cost_sum = 0, calls = 0;
      std::vector<double> p50s, p99s;
      for (auto* r : rs) {
        if (!r->success) continue;
        cost_sum += r->cost_ms_mean * r->iterations;
        calls += r->iterations;
        p50s.push_back(r->cost_ms_p50);
        p99s.push_back(r->cost_ms_p99);
      }
      md << "| " << densityLabel(d) << " | " << m << " | " << fmt(it.avg, 1) << " | "
         << fmt(f.avg, 1) << " | " << fmt(s.avg, 1) << " | " << fmt(e.avg, 1) << " | "
         << fmt(calls > 0 ? cost_sum / calls : NAN, 3) << " | " << fmt(statOf(p50s).avg, 3) << " | "
         << fmt(statOf(p99s).max, 3) << " |\n";
    }
    const PaperFigures p = paperFigures(d);
    if (std::isfinite(p.iterations_mmh)) {
      md << "| " << densityLabel(d) << " | *paper MMH* | " << fmt(p.iterations_mmh, 1)
         << " | | | | " << fmt(p.cost_ms_mmh, 1) << " | | |\n";
    }
  }
  md << "\nPaper figures from docs/benchmark.md (paper's machine: i9-13980HX; ours: 2 shared "
        "cores).\n";
  md << "\n" << stopCensusMarkdown(results);
  md << "\n" << timeByModeMarkdown(results);
  md << "\n" << energyByModeMarkdown(results);
  return md.str();
}

}  // namespace mmh::bench
