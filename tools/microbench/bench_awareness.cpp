// Awareness (paper Algorithm 1) on forest scenarios: one evaluation from start towards target.
#include <benchmark/benchmark.h>

#include <map>

#include "mmh/common/awareness.hpp"
#include "scenarios.hpp"

namespace {

const std::vector<mmh::PlanningScenario>& scenariosFor(int64_t density_percent) {
  static std::map<int64_t, std::vector<mmh::PlanningScenario>> cache;
  auto& scenarios = cache[density_percent];
  if (scenarios.empty()) {
    mmh::ScenarioSpec spec;
    spec.density_per_m2 = density_percent / 100.0;
    spec.maps = 4;
    spec.per_map = 10;
    scenarios = mmh::makeForestScenarios(spec);
  }
  return scenarios;
}

// Every scenario in turn: many answers stop early at the first blocked sample.
void BM_Awareness(benchmark::State& state) {
  const auto& scenarios = scenariosFor(state.range(0));
  mmh::AwarenessParams params;
  size_t i = 0;
  int unsafe = 0;
  for (auto _ : state) {
    const auto& s = scenarios[i++ % scenarios.size()];
    auto r = mmh::evaluateAwareness(*s.grid, s.start, s.target, params);
    unsafe += r.safe ? 0 : 1;
    benchmark::DoNotOptimize(r);
  }
  state.counters["unsafe_share"] =
      benchmark::Counter(static_cast<double>(unsafe) / state.iterations());
}
BENCHMARK(BM_Awareness)->Arg(0)->Arg(10)->Arg(20)->Unit(benchmark::kMicrosecond);

// The worst case: only the scenarios whose whole ray is CLEAR in a forest, so every sample of the
// full sensor range is judged and probed on both normals.
void BM_AwarenessClearRay(benchmark::State& state) {
  mmh::AwarenessParams params;
  std::vector<const mmh::PlanningScenario*> clear;
  for (const auto& s : scenariosFor(state.range(0))) {
    if (mmh::evaluateAwareness(*s.grid, s.start, s.target, params).safe) clear.push_back(&s);
  }
  if (clear.empty()) {
    state.SkipWithError("no clear scenario");
    return;
  }
  size_t i = 0;
  for (auto _ : state) {
    const auto& s = *clear[i++ % clear.size()];
    auto r = mmh::evaluateAwareness(*s.grid, s.start, s.target, params);
    benchmark::DoNotOptimize(r);
  }
  state.counters["scenarios"] = static_cast<double>(clear.size());
}
BENCHMARK(BM_AwarenessClearRay)->Arg(10)->Arg(20)->Unit(benchmark::kMicrosecond);

}  // namespace
