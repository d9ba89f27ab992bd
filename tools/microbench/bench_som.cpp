// Standard Optimization Mode on the forest scenarios of docs/benchmark.md (fully known 32 x 32 x 4
// m windows, start at rest, target 15 m away, 50 seeded scenarios per density): one whole
// Planner::plan() call per iteration, every scenario planned 4 times.
// Counters (from PlanOutput::timings, milliseconds): median / p90 of the whole call and of each
// step, wall clock (`*_ms_*`) and the thread's CPU time (`*_cpu_*`, what a call costs when the
// machine is shared); `success` = share of the scenarios where A* finds a path that end with a
// verified trajectory; `duration_vs_line` / `duration_vs_path` = flight time over the
// rest-to-rest bound L / v_max + v_max / a_max of the straight line and of the shortened A*
// path. MMH_SOM_BENCH_VERBOSE=1 prints every failure.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <vector>

#include "mmh/common/vehicle_limits.hpp"
#include "mmh/som/planner.hpp"
#include "scenarios.hpp"

namespace {

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * (v.size() - 1) + 0.5))];
}

struct Series {
  std::vector<double> wall, cpu;
  void add(const mmh::som::StepTime& t) {
    wall.push_back(t.wall_us * 1e-3);
    cpu.push_back(t.cpu_us * 1e-3);
  }
  void report(benchmark::State& state, const std::string& name, bool p90_cpu) const {
    state.counters[name + "_ms_p50"] = quantile(wall, 0.5);
    state.counters[name + "_ms_p90"] = quantile(wall, 0.9);
    state.counters[name + "_cpu_p50"] = quantile(cpu, 0.5);
    if (p90_cpu) state.counters[name + "_cpu_p90"] = quantile(cpu, 0.9);
  }
};

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
  mmh::som::SomParams params;  // the defaults are those of deploy/config/default.yaml
  mmh::som::Planner planner(params);
  {
    // Warm-up: the first call allocates A*'s per-cell arrays for the window.
    mmh::KinematicState start;
    start.position = scenarios[0].start;
    planner.plan(*scenarios[0].grid, start, scenarios[0].target);
  }
  Series total, astar, corridor, optimize, verify;
  std::vector<double> ratio_line, ratio_path, evals, polys;
  int with_path = 0, ok_with_path = 0;
  size_t i = 0;
  for (auto _ : state) {
    const mmh::PlanningScenario& s = scenarios[i % scenarios.size()];
    mmh::KinematicState start;
    start.position = s.start;
    const mmh::som::PlanOutput out = planner.plan(*s.grid, start, s.target);
    benchmark::DoNotOptimize(out.trajectory);
    total.add(out.timings.total);
    astar.add(out.timings.astar);
    corridor.add(out.timings.corridor);
    optimize.add(out.timings.optimize);
    verify.add(out.timings.verify);
    if (i < scenarios.size() && s.path_exists) {  // success counted once per scenario
      ++with_path;
      if (out.ok()) {
        ++ok_with_path;
        const double d = out.trajectory.duration();
        const auto& pm = planner.params();
        ratio_line.push_back(
            d / mmh::restToRestTime((s.target - s.start).norm(), pm.max_vel_mps, pm.max_acc_mps2));
        ratio_path.push_back(
            d / mmh::restToRestTime(mmh::pathLength(out.path), pm.max_vel_mps, pm.max_acc_mps2));
        evals.push_back(out.optimizer_evaluations);
        polys.push_back(out.corridor.polytopes.size());
      } else if (verbose) {
        std::fprintf(stderr, "scenario %zu (map %llu): %s: %s\n", i,
                     static_cast<unsigned long long>(s.map_seed), mmh::toString(out.status),
                     out.detail.c_str());
      }
    }
    ++i;
  }
  auto& c = state.counters;
  c["scenarios_with_path"] = with_path;
  c["success"] = with_path ? static_cast<double>(ok_with_path) / with_path : 0.0;
  total.report(state, "total", true);
  astar.report(state, "astar", false);
  corridor.report(state, "corridor", false);
  optimize.report(state, "optimize", false);
  c["verify_ms_p50"] = quantile(verify.wall, 0.5);
  c["duration_vs_line_p50"] = quantile(ratio_line, 0.5);
  c["duration_vs_path_p50"] = quantile(ratio_path, 0.5);
  c["duration_vs_path_p90"] = quantile(ratio_path, 0.9);
  c["evaluations_p50"] = quantile(evals, 0.5);
  c["polytopes_p50"] = quantile(polys, 0.5);
}
BENCHMARK(BM_Som)->Arg(10)->Arg(20)->Iterations(200)->Unit(benchmark::kMillisecond);

}  // namespace
