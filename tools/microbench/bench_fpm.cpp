// Fast Planning Mode: one planning call per iteration (FPM ignores obstacles, so the forest
// scenarios only provide starts and targets 15 m apart in every direction).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "mmh/fpm/planner.hpp"
#include "scenarios.hpp"

namespace {

mmh::fpm::Params benchParams() {
  mmh::fpm::Params p;  // the defaults equal deploy/config/default.yaml
  p.geofence_min_m = Eigen::Vector3d(-1e3, -1e3, -1e3);
  p.geofence_max_m = Eigen::Vector3d(1e3, 1e3, 1e3);
  return p;
}

std::vector<mmh::fpm::Request> restToRest() {
  mmh::ScenarioSpec spec;
  spec.density_per_m2 = 0.0;
  spec.maps = 1;
  spec.per_map = 40;
  std::vector<mmh::fpm::Request> out;
  for (const auto& s : mmh::makeForestScenarios(spec)) {
    mmh::fpm::Request r;
    r.start.position = s.start;
    r.target = s.target;
    out.push_back(r);
  }
  return out;
}

// Replanning in flight: the start moves at up to v_max in a random direction (mostly towards
// the target) with some acceleration, the target 15 m away.
std::vector<mmh::fpm::Request> movingStarts() {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0), speed(0.5, 3.0);
  std::vector<mmh::fpm::Request> out;
  for (int i = 0; i < 40; ++i) {
    mmh::fpm::Request r;
    r.start.position = Eigen::Vector3d(0.0, 0.0, 1.2);
    const double a = M_PI * u(rng);
    r.target = r.start.position + 15.0 * Eigen::Vector3d(std::cos(a), std::sin(a), 0.0);
    const double b = a + 0.6 * u(rng);  // heading within ~35 degrees of the target
    r.start.velocity = speed(rng) * Eigen::Vector3d(std::cos(b), std::sin(b), 0.1 * u(rng));
    r.start.acceleration = Eigen::Vector3d(u(rng), u(rng), 0.0) * 0.5;
    out.push_back(r);
  }
  return out;
}

// Counters: failed calls, mean duration T_s, and T_over_bound: the duration over the lower bound
// of a rest-to-rest flight along the straight line, L / v_max + v_max / a_max (docs/benchmark.md),
// or over L / v_max + v_max / (2 a_max) for a start already at v_max towards the target (0 when
// the requests have no such bound).
void runPlanner(benchmark::State& state, const std::vector<mmh::fpm::Request>& requests,
                bool has_bound) {
  const mmh::fpm::Planner planner(benchParams());
  size_t i = 0;
  int failed = 0;
  double duration_sum = 0.0, ratio_sum = 0.0;
  for (auto _ : state) {
    const auto& r = requests[i++ % requests.size()];
    auto result = planner.plan(r);
    benchmark::DoNotOptimize(result);
    if (!result.ok) {
      ++failed;
      continue;
    }
    const double T = result.trajectory.duration();
    const double L = (r.target - r.start.position).norm();
    const double bound = r.start.velocity.norm() > 0.0 ? L / 3.0 + 0.75 : L / 3.0 + 1.5;
    duration_sum += T;
    ratio_sum += has_bound ? T / bound : 0.0;
  }
  const double ok = static_cast<double>(std::max<int64_t>(1, state.iterations() - failed));
  state.counters["failed"] = benchmark::Counter(failed);
  state.counters["T_s"] = benchmark::Counter(duration_sum / ok);
  state.counters["T_over_bound"] = benchmark::Counter(ratio_sum / ok);
}

void BM_FpmRestToRest15m(benchmark::State& state) {
  static const auto requests = restToRest();
  runPlanner(state, requests, true);
}
BENCHMARK(BM_FpmRestToRest15m)->Unit(benchmark::kMicrosecond);

void BM_FpmMovingStart15m(benchmark::State& state) {
  static const auto requests = movingStarts();
  runPlanner(state, requests, false);
}
BENCHMARK(BM_FpmMovingStart15m)->Unit(benchmark::kMicrosecond);

void BM_FpmRestToRest40m(benchmark::State& state) {
  mmh::fpm::Request r;
  r.start.position = Eigen::Vector3d(-19.95, 0.0, 1.2);
  r.target = Eigen::Vector3d(19.95, 0.0, 1.2);
  runPlanner(state, {r}, true);
}
BENCHMARK(BM_FpmRestToRest40m)->Unit(benchmark::kMicrosecond);

// Replanning while cruising: at v_max straight towards a target 15 m ahead (keep cruising, brake
// at the end).
void BM_FpmCruising15m(benchmark::State& state) {
  mmh::fpm::Request r;
  r.start.position = Eigen::Vector3d(0.0, 0.0, 1.2);
  r.start.velocity = Eigen::Vector3d(3.0, 0.0, 0.0);
  r.target = Eigen::Vector3d(15.0, 0.0, 1.2);
  runPlanner(state, {r}, true);
}
BENCHMARK(BM_FpmCruising15m)->Unit(benchmark::kMicrosecond);

}  // namespace
