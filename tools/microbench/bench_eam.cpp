// Emergency Avoidance Mode on forest scenarios (SOM's scenario set: 0.1 and 0.2 obs/m^2, fully
// known 32 x 32 x 4 m windows, start at rest, target 15 m away, 50 scenarios each) with a new
// pillar inserted across the current trajectory. Two kinds of current trajectory:
//   /0  straight, time-optimal-ish (smooth trapezoid in speed) from start to target; it crosses
//       forest trees as well as the new pillar;
//   /1  collision-free: EAM's own answer on the forest before the pillar appears (the situation
//       EAM exists for: only the new obstacle threatens the committed trajectory).
// Every call is timed on its own; counters give the median / p90 call time, the success rate
// over scenarios that have a path, how often the narrow weights were chosen, and the excess of
// the exact max speed / acceleration over the limits.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <map>
#include <random>

#include "eam_scenarios.hpp"

namespace {

using mmh::eam_bench::benchParams;
using mmh::eam_bench::EamScenario;
using mmh::eam_bench::EamSet;
using mmh::eam_bench::makeSet;
using mmh::eam_bench::setPillar;

// CPU time of this thread: unlike wall-clock time, not inflated when other processes share
// the cores.
double threadCpuUs() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e6 + ts.tv_nsec * 1e-3;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t i =
      std::min(v.size() - 1, static_cast<size_t>(std::floor(q * (v.size() - 1) + 0.5)));
  return v[i];
}

void BM_EamNewPillar(benchmark::State& state) {
  const double density = state.range(0) / 100.0;
  const bool committed = state.range(1) != 0;
  static std::map<std::pair<int64_t, int64_t>, EamSet> cache;
  EamSet& set = cache[{state.range(0), state.range(1)}];
  if (set.scenarios.empty()) set = makeSet(density, committed);
  mmh::eam::Planner planner(benchParams());
  const double vmax = planner.params().max_vel_mps, amax = planner.params().max_acc_mps2;

  std::vector<double> call_us, cpu_us, split[4], evaluations;
  std::vector<int> ok(set.scenarios.size(), -1), narrow(set.scenarios.size(), 0);
  std::vector<double> v_excess, a_excess;
  std::map<int, int> failures;
  int active = -1;
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ % set.scenarios.size();
    const EamScenario& sc = set.scenarios[k];
    if (!sc.path_exists) continue;
    mmh::VoxelGrid& grid = *set.grids[sc.map];
    if (active != static_cast<int>(k)) {
      state.PauseTiming();
      if (active >= 0) {
        const EamScenario& old = set.scenarios[active];
        setPillar(*set.grids[old.map], old.pillar, false);
      }
      setPillar(grid, sc.pillar, true);
      active = static_cast<int>(k);
      state.ResumeTiming();
    }
    mmh::eam::PlanRequest req;
    req.start.position = sc.start;
    req.target = sc.target;
    req.reference = sc.reference;
    const double c0 = threadCpuUs();
    const auto t0 = std::chrono::steady_clock::now();
    const mmh::eam::PlanResult r = planner.plan(grid, req);
    const auto t1 = std::chrono::steady_clock::now();
    const double c1 = threadCpuUs();
    benchmark::DoNotOptimize(r);
    call_us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    cpu_us.push_back(c1 - c0);
    split[0].push_back(r.stats.astar_us);
    split[1].push_back(r.stats.optimize_us);
    split[2].push_back(r.stats.check_us);
    split[3].push_back(r.stats.verify_us);
    evaluations.push_back(r.stats.evaluations);
    if (ok[k] < 0) {
      ok[k] = r.ok ? 1 : 0;
      narrow[k] = r.narrow ? 1 : 0;
      if (r.ok) {
        v_excess.push_back(std::max(0.0, r.stats.max_speed / vmax - 1.0));
        a_excess.push_back(std::max(0.0, r.stats.max_acc / amax - 1.0));
      } else {
        ++failures[static_cast<int>(r.reason)];
      }
    }
  }
  if (active >= 0) {
    const EamScenario& old = set.scenarios[active];
    setPillar(*set.grids[old.map], old.pillar, false);
  }
  int tried = 0, succeeded = 0, narrowed = 0, with_path = 0;
  for (size_t k = 0; k < set.scenarios.size(); ++k) {
    with_path += set.scenarios[k].path_exists ? 1 : 0;
    if (ok[k] < 0) continue;
    ++tried;
    succeeded += ok[k];
    narrowed += narrow[k];
  }
  state.counters["scenarios_with_path"] = with_path;
  state.counters["success_rate"] = tried ? static_cast<double>(succeeded) / tried : 0.0;
  state.counters["narrow_share"] = tried ? static_cast<double>(narrowed) / tried : 0.0;
  state.counters["p50_us"] = percentile(call_us, 0.5);
  state.counters["p90_us"] = percentile(call_us, 0.9);
  state.counters["max_us"] = percentile(call_us, 1.0);
  state.counters["cpu_p50_us"] = percentile(cpu_us, 0.5);
  // Median time of each part (wall clock inside the planner) and of L-BFGS evaluations.
  state.counters["astar_p50_us"] = percentile(split[0], 0.5);
  state.counters["optimize_p50_us"] = percentile(split[1], 0.5);
  state.counters["check_p50_us"] = percentile(split[2], 0.5);
  state.counters["verify_p50_us"] = percentile(split[3], 0.5);
  state.counters["evals_p50"] = percentile(evaluations, 0.5);
  state.counters["cpu_p90_us"] = percentile(cpu_us, 0.9);
  state.counters["v_excess_p50"] = percentile(v_excess, 0.5);
  state.counters["v_excess_max"] = percentile(v_excess, 1.0);
  state.counters["a_excess_p50"] = percentile(a_excess, 0.5);
  state.counters["a_excess_max"] = percentile(a_excess, 1.0);
  for (const auto& [reason, n] : failures) {
    state.counters[std::string("fail_") + mmh::toString(static_cast<mmh::PlanStatus>(reason))] = n;
  }
}
// Args: density x 100, reference kind (0 straight, 1 committed collision-free).
BENCHMARK(BM_EamNewPillar)
    ->Args({10, 0})
    ->Args({20, 0})
    ->Args({10, 1})
    ->Args({20, 1})
    ->Unit(benchmark::kMicrosecond)
    ->Iterations(500);

}  // namespace
