// Standard Optimization Mode on the forest scenarios of BENCHMARK.md (fully known 32 x 32 x 4 m
// windows, start at rest, target 15 m away, 50 seeded scenarios per density): one whole
// Planner::plan() call per iteration. Counters: success share among the scenarios where A*
// finds a path, median / p90 of the whole call and of each step (from PlanOutput::timings),
// and the trajectory duration against the rest-to-rest bound of the straight line and of the
// shortened A* path. MMH_SOM_BENCH_VERBOSE=1 prints every failure.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <vector>

#include "mmh/som/planner.hpp"
#include "scenarios.hpp"

namespace {

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * (v.size() - 1) + 0.5))];
}

void BM_Som(benchmark::State& state) {
  static std::map<int64_t, std::vector<mmh::PlanningScenario>> cache;
  auto& scenarios = cache[state.range(0)];
  if (scenarios.empty()) {
    mmh::ScenarioSpec spec;
    spec.density_per_m2 = state.range(0) / 100.0;
    spec.maps = 10;
    spec.per_map = 5;
    scenarios = mmh::makeForestScenarios(spec);
  }
  const bool verbose = std::getenv("MMH_SOM_BENCH_VERBOSE") != nullptr;
  mmh::som::SomParams params;  // defaults = deploy/config/default.yaml
  mmh::som::Planner planner(params);
  std::vector<double> total, astar, corridor, optimize, verify, ratio_line, ratio_path, evals,
      polys;
  int with_path = 0, ok_with_path = 0;
  size_t i = 0;
  for (auto _ : state) {
    const mmh::PlanningScenario& s = scenarios[i % scenarios.size()];
    mmh::KinematicState start;
    start.position = s.start;
    const mmh::som::PlanOutput out = planner.plan(*s.grid, start, s.target);
    benchmark::DoNotOptimize(out.trajectory);
    total.push_back(out.timings.total_us * 1e-3);
    astar.push_back(out.timings.astar_us * 1e-3);
    corridor.push_back(out.timings.corridor_us * 1e-3);
    optimize.push_back(out.timings.optimize_us * 1e-3);
    verify.push_back(out.timings.verify_us * 1e-3);
    if (i < scenarios.size() && s.path_exists) {  // success counted once per scenario
      ++with_path;
      if (out.ok()) {
        ++ok_with_path;
        const double d = out.trajectory.duration();
        const auto& pm = planner.params();
        ratio_line.push_back(d / mmh::som::restToRestTimeBound((s.target - s.start).norm(),
                                                               pm.max_vel_mps, pm.max_acc_mps2));
        ratio_path.push_back(d / mmh::som::restToRestTimeBound(mmh::pathLength(out.path),
                                                               pm.max_vel_mps, pm.max_acc_mps2));
        evals.push_back(out.optimizer_evaluations);
        polys.push_back(out.corridor.polytopes.size());
      } else if (verbose) {
        std::fprintf(stderr, "scenario %zu (map %llu): %s: %s\n", i,
                     static_cast<unsigned long long>(s.map_seed), mmh::som::toString(out.status),
                     out.detail.c_str());
      }
    }
    ++i;
  }
  auto& c = state.counters;
  c["scenarios_with_path"] = with_path;
  c["success"] = with_path ? static_cast<double>(ok_with_path) / with_path : 0.0;
  c["total_ms_p50"] = quantile(total, 0.5);
  c["total_ms_p90"] = quantile(total, 0.9);
  c["astar_ms_p50"] = quantile(astar, 0.5);
  c["astar_ms_p90"] = quantile(astar, 0.9);
  c["corridor_ms_p50"] = quantile(corridor, 0.5);
  c["corridor_ms_p90"] = quantile(corridor, 0.9);
  c["optimize_ms_p50"] = quantile(optimize, 0.5);
  c["optimize_ms_p90"] = quantile(optimize, 0.9);
  c["verify_ms_p50"] = quantile(verify, 0.5);
  c["duration_vs_line_p50"] = quantile(ratio_line, 0.5);
  c["duration_vs_path_p50"] = quantile(ratio_path, 0.5);
  c["duration_vs_path_p90"] = quantile(ratio_path, 0.9);
  c["evaluations_p50"] = quantile(evals, 0.5);
  c["polytopes_p50"] = quantile(polys, 0.5);
}
// Each of the 50 scenarios is planned 4 times (timings over all calls, success once each).
BENCHMARK(BM_Som)->Arg(10)->Arg(20)->Iterations(200)->Unit(benchmark::kMillisecond);

}  // namespace
