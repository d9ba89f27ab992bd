// The arbiter's stop choice on forest scenarios: a vehicle at 3 m/s flying straight at its target
// through the trees, where braking often meets a trunk and the swerving stops are searched.
#include <benchmark/benchmark.h>

#include <map>

#include "mmh/common/collision_check.hpp"
#include "mmh/common/minco.hpp"
#include "mmh/common/stopping_trajectory.hpp"
#include "scenarios.hpp"

namespace {

constexpr double kSpeedMps = 3.0;
constexpr double kMaxAccMps2 = 2.0;
constexpr double kClearanceM = 0.25;  // the arbiter's check_inflation_m
constexpr double kTouchM = 0.2;

struct StopCase {
  mmh::PlanningScenario scenario;
  mmh::Trajectory path;  // straight at kSpeedMps from the start through the target
};

const std::vector<StopCase>& casesFor(int64_t density_percent) {
  static std::map<int64_t, std::vector<StopCase>> cache;
  auto& cases = cache[density_percent];
  if (cases.empty()) {
    mmh::ScenarioSpec spec;
    spec.density_per_m2 = density_percent / 100.0;
    spec.maps = 4;
    spec.per_map = 10;
    spec.inflation_m = kClearanceM;
    for (const auto& s : mmh::makeForestScenarios(spec)) {
      const Eigen::Vector3d v = (s.target - s.start).normalized() * kSpeedMps;
      const double duration = (s.target - s.start).norm() / kSpeedMps;
      mmh::MincoJerk m;
      Eigen::Matrix3d head, tail;
      head << s.start, v, Eigen::Vector3d::Zero();
      tail << s.target, v, Eigen::Vector3d::Zero();
      m.setConditions(head, tail, 1);
      m.setParameters(Eigen::Matrix3Xd(3, 0), Eigen::VectorXd::Constant(1, duration));
      cases.push_back({s, m.trajectory()});
    }
  }
  return cases;
}

// One choice per scenario in turn, from 1 s before the first tree the path meets (or from its
// start when it meets none).
void BM_StopChoice(benchmark::State& state) {
  const auto& cases = casesFor(state.range(0));
  size_t i = 0;
  for (auto _ : state) {
    const StopCase& c = cases[i++ % cases.size()];
    const auto hit = mmh::firstCollisionTime(*c.scenario.grid, c.path, 0.0, c.path.duration());
    const double t0 = hit ? std::max(0.0, *hit - 1.0) : 0.0;
    const mmh::Trajectory stop = mmh::chooseStoppingTrajectory(
        c.scenario.grid.get(), c.path, t0, kMaxAccMps2, kSpeedMps, kClearanceM, kTouchM);
    benchmark::DoNotOptimize(stop);
  }
}
BENCHMARK(BM_StopChoice)->Arg(10)->Arg(20)->Unit(benchmark::kMicrosecond);

}  // namespace
