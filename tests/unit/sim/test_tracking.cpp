// The flight controller's tracking model (mmh-sim --follow setpoint) against known answers, the
// vehicle flying setpoints, and the mission monitor's waypoint arrivals and tracking error.
#include <gtest/gtest.h>

#include <cmath>

#include "mmh/sim/forest_world.hpp"
#include "mmh/sim/mission.hpp"
#include "mmh/sim/tracking_model.hpp"
#include "mmh/sim/vehicle.hpp"
#include "traj_helpers.hpp"

using Eigen::Vector3d;
using mmh::KinematicState;
using mmh::sim::SetpointSample;
using mmh::sim::TrackingParams;

namespace {
constexpr int64_t kT0 = 1'000'000'000;
constexpr int64_t kStep = 10'000;

SetpointSample onTrajectory(const mmh::Trajectory& traj, int64_t utime, double t) {
  SetpointSample s;
  s.utime = utime;
  s.trajectory_id = 1;
  s.on_trajectory = true;
  s.state = traj.state(t);
  s.jerk = traj.derivative(3, std::min(t, traj.duration()));
  return s;
}
}  // namespace

TEST(TrackingModel, AStepIsApproachedCriticallyDampedWithinTheAccelerationLimit) {
  TrackingParams p;  // 1 Hz, critically damped, 4 m/s^2
  KinematicState v;
  KinematicState ref;
  ref.position = Vector3d(0.05, 0, 0);  // small: the limit stays inactive, the answer is linear
  const double w = 2 * M_PI;
  double max_x = 0.0;
  for (int i = 1; i <= 300; ++i) {
    v = mmh::sim::trackingStep(v, ref, 0.001, p);
    max_x = std::max(max_x, v.position.x());
    const double t = i * 0.001;
    // x(t) = d (1 - (1 + w t) e^{-w t}) for a critically damped second-order loop.
    EXPECT_NEAR(v.position.x(), 0.05 * (1 - (1 + w * t) * std::exp(-w * t)), 2e-4) << t;
  }
  EXPECT_LE(max_x, 0.05 + 1e-12);  // no overshoot
  // A large step saturates at the acceleration limit.
  KinematicState far;
  ref.position = Vector3d(10, 0, 0);
  far = mmh::sim::trackingStep(far, ref, 0.01, p);
  EXPECT_NEAR(far.acceleration.norm(), 4.0, 1e-12);
}

TEST(TrackingModel, ASetpointIsCarriedForwardAlongItsDerivativesThenHeld) {
  TrackingParams p;
  SetpointSample s;
  s.utime = kT0;
  s.state.position = Vector3d(1, 0, 0);
  s.state.velocity = Vector3d(2, 0, 0);
  s.state.acceleration = Vector3d(0, 1, 0);
  s.jerk = Vector3d(0, 0, 6);
  const KinematicState r = mmh::sim::referenceAt(s, kT0 + 50'000, p);
  EXPECT_NEAR((r.position - Vector3d(1.1, 0.00125, 0.000125)).norm(), 0, 1e-12);
  EXPECT_NEAR((r.velocity - Vector3d(2, 0.05, 0.0075)).norm(), 0, 1e-12);
  const KinematicState stale = mmh::sim::referenceAt(s, kT0 + 500'000, p);
  EXPECT_NEAR(stale.position.x(), 1.2, 1e-12);  // carried 0.1 s, then held at rest
  EXPECT_EQ(stale.velocity, Vector3d::Zero());
}

TEST(TrackingModel, TheVehicleFollowsSetpointsWithASmallMeasuredError) {
  mmh::sim::SimParams params;
  const Vector3d start(0, 0, 1);
  mmh::sim::Vehicle vehicle(start, 0.0, kT0, params);
  vehicle.followSetpoints();
  auto traj = mmh::test::minJerkTraj(start, Vector3d(6, 2, 1), 5.0);
  double max_error = 0.0;
  for (int64_t now = kT0; now < kT0 + 7'000'000; now += kStep) {
    vehicle.setSetpoint(onTrajectory(*traj, now, (now - kT0) * 1e-6));  // sampled at 100 Hz
    vehicle.advance(now + kStep, nullptr);
    ASSERT_TRUE(vehicle.trackingError().has_value());
    max_error = std::max(max_error, *vehicle.trackingError());
    EXPECT_LE(vehicle.state().acceleration.norm(), params.tracking.max_acc_mps2 + 1e-12);
  }
  // With velocity and acceleration fed forward the loop only corrects the step's discretisation.
  EXPECT_LT(max_error, 0.01);
  EXPECT_GT(max_error, 0.0);
  EXPECT_NEAR((vehicle.state().position - Vector3d(6, 2, 1)).norm(), 0.0, 0.01);
  EXPECT_NEAR(vehicle.modelDistance(), std::sqrt(40.0), 0.02);
  EXPECT_EQ(vehicle.firstTrajectoryUtime(), kT0);
}

TEST(TrackingModel, WithoutFeedForwardTheErrorIsTheLoopsLag) {
  // A setpoint moving at constant speed without velocity feed-forward: the steady lag of a
  // critically damped loop is 2 zeta v / w.
  TrackingParams p;
  KinematicState v;
  for (int i = 0; i < 2000; ++i) {
    KinematicState ref;
    ref.position = Vector3d(i * 0.001 * 1.0, 0, 0);
    v = mmh::sim::trackingStep(v, ref, 0.001, p);
  }
  EXPECT_NEAR(1.999 - v.position.x(), 2.0 * 1.0 / (2 * M_PI), 0.01);
}

TEST(MissionWaypoints, ArrivalsAreListedAndTheMissionIsReachedAtTheLast) {
  const mmh::sim::ForestWorld empty({});
  mmh::sim::SimParams params;
  const Vector3d start(0, 0, 1);
  mmh::sim::MissionMonitor monitor(empty, params, start, Vector3d(3, 0, 1));
  mmh::sim::Vehicle vehicle(start, 0.0, kT0, params);
  auto traj = mmh::test::minJerkTraj(start, Vector3d(9, 0, 1), 6.0);
  vehicle.commit(traj, kT0, 1);
  const auto goal = [&](double x, int index, bool stop) {
    mmh::sim::MissionGoal g;
    g.position = Vector3d(x, 0, 1);
    g.goal_id = 1 + index;
    g.waypoint_index = index;
    g.num_waypoints = 3;
    g.tolerance_m = stop ? 0.3 : 1.0;
    g.stop = stop;
    monitor.setMissionGoal(g);
  };
  goal(3, 0, false);
  std::vector<mmh::sim::FlownPart> flown;
  for (int64_t now = kT0 + kStep; now <= kT0 + 8'000'000; now += kStep) {
    flown.clear();
    vehicle.advance(now, &flown);
    monitor.update(now, vehicle, flown);
    const auto& m = monitor.metrics();
    // The executor hands the next waypoint over at each arrival.
    if (m.arrivals.size() == 1 && m.waypoint_index == 0) goal(6, 1, false);
    if (m.arrivals.size() == 2 && m.waypoint_index == 1) goal(9, 2, true);
    if (m.waypoint_index < 2) {
      EXPECT_FALSE(m.reached);
    }
  }
  const auto& m = monitor.metrics();
  ASSERT_EQ(m.arrivals.size(), 3u);
  EXPECT_TRUE(m.reached);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(m.arrivals[i].waypoint_index, i);
  // Passed at speed (within 1 m, mid-flight), stopped at the last.
  EXPECT_GT(m.arrivals[0].speed_mps, 1.0);
  EXPECT_GT(m.arrivals[1].speed_mps, 1.0);
  EXPECT_LE(m.arrivals[2].speed_mps, params.mission_stop_speed_mps);
  EXPECT_LT(m.arrivals[0].flight_time_s, m.arrivals[1].flight_time_s);
  EXPECT_FALSE(m.follows_setpoints);
}
