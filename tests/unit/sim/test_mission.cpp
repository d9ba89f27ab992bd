// Mission metrics against analytic answers: jerk energy of known polynomials (also across a
// trajectory switch), flown distance, flight time to arrival, collisions and the time bound.
#include <gtest/gtest.h>

#include <cmath>

#include "mmh/sim/forest_world.hpp"
#include "mmh/sim/mission.hpp"
#include "traj_helpers.hpp"

using Eigen::Vector3d;

namespace {
constexpr int64_t kT0 = 1'000'000'000;
constexpr int64_t kStep = 10'000;

mmh::Trajectory poly(int axis, int power, double duration) {
  mmh::Piece p;
  p.duration = duration;
  p.coeffs(axis, power) = 1.0;
  return mmh::Trajectory({p});
}
}  // namespace

TEST(JerkEnergy, KnownPolynomials) {
  // x = t^3: jerk 6, energy 36 per second.
  EXPECT_NEAR(mmh::sim::jerkEnergy(poly(0, 3, 2.0), 0.0, 2.0), 72.0, 1e-9);
  EXPECT_NEAR(mmh::sim::jerkEnergy(poly(0, 3, 2.0), 0.5, 1.5), 36.0, 1e-9);
  // y = t^4: jerk 24 t, energy 576 t^3 / 3.
  EXPECT_NEAR(mmh::sim::jerkEnergy(poly(1, 4, 1.0), 0.0, 1.0), 192.0, 1e-9);
  EXPECT_NEAR(mmh::sim::jerkEnergy(poly(1, 4, 1.0), 0.5, 1.0), 192.0 * (1 - 0.125), 1e-9);
  // Two pieces: the integral splits at the boundary; the whole equals Trajectory::jerkEnergy.
  mmh::Trajectory two({mmh::test::minJerk(Vector3d(0, 0, 0), Vector3d(1, 2, 0), 1.5),
                       mmh::test::minJerk(Vector3d(1, 2, 0), Vector3d(3, 2, 1), 2.0)});
  EXPECT_NEAR(mmh::sim::jerkEnergy(two, 0.0, 3.5), two.jerkEnergy(), 1e-9);
  EXPECT_NEAR(mmh::sim::jerkEnergy(two, 0.0, 1.0) + mmh::sim::jerkEnergy(two, 1.0, 3.5),
              two.jerkEnergy(), 1e-9);
  // Minimum-jerk rest to rest over distance D in time T: 720 D^2 / T^5.
  mmh::Trajectory mj({mmh::test::minJerk(Vector3d::Zero(), Vector3d(2, 0, 0), 2.0)});
  EXPECT_NEAR(mmh::sim::jerkEnergy(mj, 0.0, 2.0), 720.0 * 4.0 / 32.0, 1e-9);
}

TEST(Mission, ObstacleFreeBoundIs14_8s) {
  const mmh::sim::ForestWorld empty({});
  mmh::sim::MissionMonitor monitor(empty, mmh::sim::SimParams{}, Vector3d(-19.95, 0, 1.2),
                                   Vector3d(19.95, 0, 1.2));
  EXPECT_NEAR(monitor.metrics().shortest_path_m, 39.9, 1e-12);
  EXPECT_NEAR(monitor.metrics().time_bound_s, 14.8, 1e-12);
}

TEST(Mission, StraightFlightDistanceTimeEnergyAndArrival) {
  const mmh::sim::ForestWorld empty({});
  mmh::sim::SimParams params;
  const Vector3d start(0, 0, 1), goal(4, 0, 1);
  mmh::sim::MissionMonitor monitor(empty, params, start, goal);
  mmh::sim::Vehicle vehicle(start, 0.0, kT0, params);
  auto traj = mmh::test::minJerkTraj(start, goal, 4.0);
  const int64_t ts = kT0 + 100'000;
  vehicle.commit(traj, ts, 1);
  std::vector<mmh::sim::FlownPart> flown;
  int64_t now = kT0;
  while (!monitor.metrics().reached && now < kT0 + 10'000'000) {
    now += kStep;
    flown.clear();
    vehicle.advance(now, &flown);
    monitor.update(now, vehicle, flown);
  }
  const auto& m = monitor.metrics();
  ASSERT_TRUE(m.reached);
  EXPECT_FALSE(m.collided);
  // Arrival: the first step with the vehicle within 0.3 m, i.e. x >= 3.7.
  double t_arrive = 0.0;
  while (traj->position(t_arrive).x() < 3.7) t_arrive += 0.01;
  EXPECT_NEAR(m.flight_time_s, (m.arrival_utime - ts) * 1e-6, 1e-12);
  EXPECT_NEAR(m.flight_time_s, t_arrive, 0.011);
  EXPECT_NEAR(m.distance_m, traj->position((m.arrival_utime - ts) * 1e-6).x(), 1e-6);
  EXPECT_NEAR(m.energy, mmh::sim::jerkEnergy(*traj, 0.0, (m.arrival_utime - ts) * 1e-6), 1e-9);
  EXPECT_TRUE(std::isinf(m.min_clearance_m));
  // Metrics stop at arrival.
  const double d = m.distance_m;
  now += kStep;
  flown.clear();
  vehicle.advance(now, &flown);
  monitor.update(now, vehicle, flown);
  EXPECT_EQ(monitor.metrics().distance_m, d);
}

TEST(Mission, EnergyAndDistanceAccumulateAcrossASwitch) {
  const mmh::sim::ForestWorld empty({});
  mmh::sim::SimParams params;
  const Vector3d start(0, 0, 1);
  mmh::sim::MissionMonitor monitor(empty, params, start, Vector3d(100, 0, 1));
  mmh::sim::Vehicle vehicle(start, 0.0, kT0, params);
  mmh::Trajectory a_traj({mmh::test::minJerk(start, Vector3d(2, 1, 1), 2.0)});
  auto a = std::make_shared<const mmh::Trajectory>(a_traj);
  vehicle.commit(a, kT0, 1);
  // The second starts at 1.234 s where the first is, with the first's state there (continuous
  // position, velocity and acceleration): a cubic Taylor start then a quintic-like shape.
  const double ts = 1.234;
  mmh::Piece p;
  p.duration = 3.0;
  const mmh::KinematicState s = a->state(ts);
  p.coeffs.col(0) = s.position;
  p.coeffs.col(1) = s.velocity;
  p.coeffs.col(2) = 0.5 * s.acceleration;
  p.coeffs.col(3) = Vector3d(0.1, -0.2, 0.05);
  auto b = std::make_shared<const mmh::Trajectory>(mmh::Trajectory({p}));
  vehicle.commit(b, kT0 + 1'234'000, 2);
  std::vector<mmh::sim::FlownPart> flown;
  for (int i = 1; i <= 300; ++i) {
    flown.clear();
    vehicle.advance(kT0 + i * kStep, &flown);
    monitor.update(kT0 + i * kStep, vehicle, flown);
  }
  const auto& m = monitor.metrics();
  const double expected_energy =
      mmh::sim::jerkEnergy(*a, 0.0, ts) + mmh::sim::jerkEnergy(*b, 0.0, 3.0 - ts);
  EXPECT_NEAR(m.energy, expected_energy, 1e-9);
  EXPECT_NEAR(m.distance_m, a->arcLength(0.0, ts) + b->arcLength(0.0, 3.0 - ts), 1e-9);
  EXPECT_EQ(m.trajectory_jumps, 0);
  EXPECT_NEAR(m.flight_time_s, 3.0, 1e-12);
}

TEST(Mission, CurvedPathDistanceIsItsArcLength) {
  // y = x^2 for x in [0, 1] at unit speed in x: arc length (2 sqrt 5 + asinh 2) / 4.
  const mmh::sim::ForestWorld empty({});
  mmh::sim::SimParams params;
  mmh::sim::MissionMonitor monitor(empty, params, Vector3d(0, 0, 1), Vector3d(50, 0, 1));
  mmh::sim::Vehicle vehicle(Vector3d(0, 0, 1), 0.0, kT0, params);
  mmh::Piece p;
  p.duration = 1.0;
  p.coeffs(0, 1) = 1.0;
  p.coeffs(1, 2) = 1.0;
  p.coeffs(2, 0) = 1.0;
  vehicle.commit(std::make_shared<const mmh::Trajectory>(mmh::Trajectory({p})), kT0, 1);
  std::vector<mmh::sim::FlownPart> flown;
  for (int i = 1; i <= 150; ++i) {
    flown.clear();
    vehicle.advance(kT0 + i * kStep, &flown);
    monitor.update(kT0 + i * kStep, vehicle, flown);
  }
  EXPECT_NEAR(monitor.metrics().distance_m, (2 * std::sqrt(5.0) + std::asinh(2.0)) / 4.0, 1e-9);
}

TEST(Mission, CollisionAndClearanceAgainstGroundTruth) {
  // A pillar of radius 0.3 at x = 2 on the straight line: the 0.15 m vehicle touches it when
  // its centre passes x = 2 - 0.45.
  const mmh::sim::ForestWorld world({mmh::Cylinder{Eigen::Vector2d(2, 0), 0.3, 0, 3}});
  mmh::sim::SimParams params;
  mmh::sim::MissionMonitor monitor(world, params, Vector3d(0, 0, 1), Vector3d(4, 0, 1));
  mmh::sim::Vehicle vehicle(Vector3d(0, 0, 1), 0.0, kT0, params);
  vehicle.commit(mmh::test::line(Vector3d(0, 0, 1), Vector3d(1, 0, 0), 4.0), kT0, 1);
  std::vector<mmh::sim::FlownPart> flown;
  bool event = false;
  for (int i = 1; i <= 400 && !event; ++i) {
    flown.clear();
    vehicle.advance(kT0 + i * kStep, &flown);
    event = monitor.update(kT0 + i * kStep, vehicle, flown);
  }
  const auto& m = monitor.metrics();
  EXPECT_TRUE(m.collided);
  EXPECT_FALSE(m.reached);
  EXPECT_NEAR(m.collision_position.x(), 1.55, 0.011);
  EXPECT_LT(m.min_clearance_m, 0.15);
  EXPECT_GE(m.min_clearance_m, 0.15 - 0.011);
  // The bound goes round the pillar (inflated by the radius).
  EXPECT_GT(m.shortest_path_m, 4.0);
  EXPECT_LT(m.shortest_path_m, 4.0 + 0.3);
}

TEST(Mission, ArrivalAtAGoalTheArbiterMovedWithinTheRadiusOnly) {
  const mmh::sim::ForestWorld empty({});
  mmh::sim::SimParams params;
  params.goal_relocate_radius_m = 1.5;
  const Vector3d start(0, 0, 1), goal(4, 0, 1), moved(4, 1.0, 1);
  mmh::sim::MissionMonitor monitor(empty, params, start, goal);
  monitor.setGoal(goal, 1);
  // Beyond the radius: refused, the goal sent still counts.
  EXPECT_FALSE(monitor.acceptMovedGoal(Vector3d(4, 2.0, 1), 1.5));
  EXPECT_FALSE(monitor.metrics().goal_moved);
  EXPECT_TRUE(monitor.acceptMovedGoal(moved, 1.5));
  EXPECT_TRUE(monitor.metrics().goal_moved);
  EXPECT_EQ(monitor.metrics().goal, goal);  // the goal sent, unchanged
  EXPECT_EQ(monitor.metrics().moved_goal, moved);
  // The same goal sent again keeps the moved point.
  monitor.setGoal(goal, 1);
  EXPECT_TRUE(monitor.metrics().goal_moved);
  // Fly to the moved goal: 1 m from the goal sent (beyond its 0.3 m tolerance), reached.
  mmh::sim::Vehicle vehicle(start, 0.0, kT0, params);
  vehicle.commit(mmh::test::minJerkTraj(start, moved, 4.0), kT0 + 100'000, 1);
  std::vector<mmh::sim::FlownPart> flown;
  int64_t now = kT0;
  while (!monitor.metrics().reached && now < kT0 + 10'000'000) {
    now += kStep;
    flown.clear();
    vehicle.advance(now, &flown);
    monitor.update(now, vehicle, flown);
  }
  EXPECT_TRUE(monitor.metrics().reached);
  EXPECT_LE((vehicle.state().position - moved).norm(), params.goal_tolerance_m);
  // A new goal position forgets the move.
  monitor.setGoal(Vector3d(8, 0, 1), 2);
  EXPECT_FALSE(monitor.metrics().goal_moved);
  EXPECT_FALSE(monitor.metrics().reached);
}
