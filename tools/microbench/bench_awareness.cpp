// Awareness (paper Algorithm 1) on forest scenarios: one evaluation from start towards target.
#include <benchmark/benchmark.h>

#include "mmh/common/awareness.hpp"
#include "scenarios.hpp"

namespace {

void BM_Awareness(benchmark::State& state) {
  mmh::ScenarioSpec spec;
  spec.density_per_m2 = state.range(0) / 100.0;
  spec.maps = 4;
  spec.per_map = 10;
  static std::map<int64_t, std::vector<mmh::PlanningScenario>> cache;
  auto& scenarios = cache[state.range(0)];
  if (scenarios.empty()) scenarios = mmh::makeForestScenarios(spec);
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

}  // namespace
