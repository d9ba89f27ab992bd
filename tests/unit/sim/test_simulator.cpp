// The assembled simulator: rates of frames and status, determinism, options errors.
#include <gtest/gtest.h>

#include "mmh/common/vehicle_limits.hpp"
#include "mmh/sim/shortest_path.hpp"
#include "mmh/sim/simulator.hpp"
#include "traj_helpers.hpp"

using Eigen::Vector3d;

TEST(Simulator, PublishesFramesAt15HzAndStatusAt10Hz) {
  mmh::sim::SimOptions options;
  options.density_per_m2 = 0.05;
  mmh::sim::Simulator sim(mmh::sim::SimParams{}, options);
  EXPECT_EQ(sim.nowUtime(), mmh::sim::kLockstepStartUtime);
  int scans = 0, statuses = 0;
  for (int i = 0; i < 300; ++i) {  // 3 s
    const auto r = sim.step();
    scans += r.scan;
    statuses += r.status;
  }
  EXPECT_EQ(sim.nowUtime(), mmh::sim::kLockstepStartUtime + 3'000'000);
  EXPECT_NEAR(scans, 45, 1);
  EXPECT_NEAR(statuses, 30, 1);
}

TEST(Simulator, SameOptionsSameFlight) {
  mmh::sim::SimOptions options;
  options.density_per_m2 = 0.2;
  options.seed = 4;
  mmh::sim::SimParams params;
  params.depth.range_noise_m = 0.02;
  mmh::sim::Simulator a(params, options), b(params, options);
  auto traj = mmh::test::minJerkTraj(options.start, options.start + Vector3d(1.5, 0.5, 0), 3.0);
  a.commitTrajectory(traj, a.nowUtime() + 200'000, 1);
  b.commitTrajectory(traj, b.nowUtime() + 200'000, 1);
  for (int i = 0; i < 400; ++i) {
    const auto ra = a.step();
    const auto rb = b.step();
    ASSERT_EQ(ra.scan, rb.scan);
    if (ra.scan) {
      ASSERT_EQ(a.lastScan().xyz, b.lastScan().xyz);
    }
  }
  EXPECT_EQ(a.vehicle().state().position, b.vehicle().state().position);
  EXPECT_EQ(a.metrics().distance_m, b.metrics().distance_m);
  EXPECT_EQ(a.metrics().energy, b.metrics().energy);
  EXPECT_GT(a.metrics().distance_m, 1.5);
}

TEST(Simulator, BadOptionsAreClearErrors) {
  mmh::sim::SimOptions options;
  options.world = "moon";
  EXPECT_THROW(mmh::sim::Simulator(mmh::sim::SimParams{}, options), std::runtime_error);
  options = mmh::sim::SimOptions{};
  options.sensor = "radar";
  EXPECT_THROW(mmh::sim::Simulator(mmh::sim::SimParams{}, options), std::runtime_error);
  options = mmh::sim::SimOptions{};
  options.density_per_m2 = -1.0;
  EXPECT_THROW(mmh::sim::Simulator(mmh::sim::SimParams{}, options), std::runtime_error);
}

TEST(Simulator, VeryDenseForestsStillGetABoundQuickly) {
  // 50 obstacles per m^2 (125,000 cylinders): the grid fallback, no quadratic blow-up. The forest
  // is a solid block except round start and goal, so there is no path.
  mmh::sim::SimOptions options;
  options.density_per_m2 = 50.0;
  mmh::sim::Simulator sim(mmh::sim::SimParams{}, options);
  EXPECT_LT(sim.metrics().shortest_path_m, 0.0);
}

TEST(Simulator, FinishedOnArrivalOrCollision) {
  mmh::sim::SimOptions options;
  options.density_per_m2 = 0.0;
  options.start = Vector3d(0, 0, 1.2);
  options.goal = Vector3d(2, 0, 1.2);
  mmh::sim::Simulator sim(mmh::sim::SimParams{}, options);
  sim.commitTrajectory(mmh::test::minJerkTraj(options.start, options.goal, 2.0), sim.nowUtime(), 1);
  int steps = 0;
  while (!sim.finished() && steps < 1000) {
    sim.step();
    ++steps;
  }
  EXPECT_TRUE(sim.metrics().reached);
  EXPECT_LT(steps, 200);
  EXPECT_NEAR(sim.metrics().time_bound_s, mmh::restToRestTime(2.0, 3.0, 2.0), 1e-12);
}
