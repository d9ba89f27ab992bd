// The trajectory server's rules: sampling, the switch-over exactly at a trajectory's start time
// without a jump, the hold at the end, the watchdog's brake within a_max to a hover, and the yaw.
#include <gtest/gtest.h>

#include <cmath>

#include "../sim/traj_helpers.hpp"
#include "mmh/setpoint/setpoint_server.hpp"

using Eigen::Vector3d;
using mmh::KinematicState;
using mmh::Trajectory;
using mmh::setpoint::Setpoint;
using mmh::setpoint::SetpointServer;
using mmh::setpoint::State;

namespace {

constexpr int64_t kT0 = 1'000'000'000;
constexpr int64_t kPeriod = 10'000;  // 100 Hz
int64_t at(double s) {
  return kT0 + static_cast<int64_t>(std::llround(s * 1e6));
}

mmh::setpoint::Params params() {
  mmh::setpoint::Params p;
  p.watchdog_s = 2.5;
  p.max_acc_mps2 = 2.0;
  p.max_vel_mps = 3.0;
  return p;
}

}  // namespace

TEST(SetpointServer, NothingToSampleBeforeAPositionOrATrajectory) {
  SetpointServer s(params());
  EXPECT_FALSE(s.sample(at(0)).has_value());
  s.vehicleAt(Vector3d(1, 2, 1.2), 0.5);
  const auto sp = s.sample(at(0.01));
  ASSERT_TRUE(sp.has_value());
  EXPECT_EQ(sp->state, State::kHold);
  EXPECT_EQ(sp->kinematics.position, Vector3d(1, 2, 1.2));
  EXPECT_DOUBLE_EQ(sp->yaw_rad, 0.5);
}

TEST(SetpointServer, SamplesTheTrajectoryAtItsOwnTimeAndHoldsItsEndAtRest) {
  SetpointServer s(params());
  s.vehicleAt(Vector3d(0, 0, 1), 0.0);
  auto traj = mmh::test::minJerkTraj(Vector3d(0, 0, 1), Vector3d(4, 0, 1), 4.0);
  s.commit(traj, at(1.0), 7, at(0.5));
  for (int64_t t = at(0.5); t <= at(6.0); t += kPeriod) {
    s.arbiterAlive(t);  // the planner is there: no watchdog
    const Setpoint sp = *s.sample(t);
    const double tt = (t - at(1.0)) * 1e-6;
    if (tt < 0) {
      EXPECT_EQ(sp.state, State::kHold) << tt;
    } else if (tt < 4.0) {
      EXPECT_EQ(sp.state, State::kTracking);
      EXPECT_EQ(sp.trajectory_id, 7);
      EXPECT_NEAR((sp.kinematics.position - traj->position(tt)).norm(), 0.0, 1e-12);
      EXPECT_NEAR((sp.kinematics.velocity - traj->velocity(tt)).norm(), 0.0, 1e-12);
      EXPECT_NEAR((sp.kinematics.acceleration - traj->acceleration(tt)).norm(), 0.0, 1e-12);
      EXPECT_NEAR((sp.jerk - traj->derivative(3, tt)).norm(), 0.0, 1e-9);
    } else {
      EXPECT_EQ(sp.state, State::kEnd);
      EXPECT_NEAR((sp.kinematics.position - Vector3d(4, 0, 1)).norm(), 0.0, 1e-12);
      EXPECT_EQ(sp.kinematics.velocity, Vector3d::Zero());
      EXPECT_EQ(sp.jerk, Vector3d::Zero());
    }
  }
  EXPECT_EQ(s.counters().switches, 1);
  EXPECT_EQ(s.counters().jumps, 0);
}

TEST(SetpointServer, SwitchesExactlyAtTheStartTimeWithoutAJump) {
  SetpointServer s(params());
  auto first = mmh::test::minJerkTraj(Vector3d(0, 0, 1), Vector3d(6, 0, 1), 5.0);
  s.commit(first, at(0.0), 1, at(0.0));
  // The arbiter's way: the next trajectory starts in the committed one's state at its start time,
  // here between two samples, and turns towards another target.
  const double switch_s = 2.005;
  auto second = std::make_shared<const Trajectory>(
      mmh::test::planFrom(first->state(switch_s), Vector3d(6, 3, 1), 4.0));
  s.commit(second, at(switch_s), 2, at(1.9));
  std::optional<Setpoint> previous;
  double largest_step = 0.0;
  for (int64_t t = at(0.0); t <= at(7.0); t += kPeriod) {
    s.arbiterAlive(t);
    const Setpoint sp = *s.sample(t);
    const double tt = (t - kT0) * 1e-6;
    if (tt < switch_s) {
      EXPECT_EQ(sp.trajectory_id, 1) << tt;  // not a sample early
      EXPECT_NEAR((sp.kinematics.position - first->position(tt)).norm(), 0.0, 1e-12);
    } else {
      EXPECT_EQ(sp.trajectory_id, 2) << tt;
      const double t2 = tt - switch_s;
      if (t2 < 4.0) {
        EXPECT_NEAR((sp.kinematics.position - second->position(t2)).norm(), 0.0, 1e-12);
      }
    }
    if (previous) {
      largest_step =
          std::max(largest_step, (sp.kinematics.position - previous->kinematics.position).norm());
      // No jump in velocity either: it changes by a bounded acceleration times dt.
      EXPECT_LE((sp.kinematics.velocity - previous->kinematics.velocity).norm(), 0.04);
    }
    previous = sp;
  }
  EXPECT_LE(largest_step, 3.0 * 0.01 + 1e-9);  // at most v_max * dt between two samples
  EXPECT_EQ(s.counters().switches, 2);
  EXPECT_EQ(s.counters().jumps, 0);
}

TEST(SetpointServer, ATrajectoryThatDoesNotStartWhereTheSetpointIsCountsAsAJump) {
  SetpointServer s(params());
  s.commit(mmh::test::minJerkTraj(Vector3d(0, 0, 1), Vector3d(2, 0, 1), 2.0), at(0), 1, at(0));
  s.sample(at(0.5));
  s.commit(mmh::test::minJerkTraj(Vector3d(5, 5, 1), Vector3d(6, 5, 1), 2.0), at(1.0), 2, at(0.5));
  s.sample(at(1.0));
  EXPECT_EQ(s.counters().jumps, 1);
}

TEST(SetpointServer, AnEmptyTrajectoryHoldsWhereTheSetpointIsAtItsStart) {
  SetpointServer s(params());
  auto traj = mmh::test::line(Vector3d(0, 0, 1), Vector3d(1, 0, 0), 10.0);
  s.commit(traj, at(0), 1, at(0));
  s.commit(std::make_shared<const Trajectory>(), at(2.0), 2, at(1.0));
  for (int64_t t = at(0); t <= at(3.0); t += kPeriod) s.sample(t);
  const Setpoint sp = *s.sample(at(3.0));
  EXPECT_EQ(sp.state, State::kHold);
  EXPECT_NEAR((sp.kinematics.position - Vector3d(2, 0, 1)).norm(), 0.0, 1e-9);
  EXPECT_EQ(sp.kinematics.velocity, Vector3d::Zero());
}

TEST(SetpointServer, HeartbeatsOfTheArbiterKeepTheWatchdogQuiet) {
  SetpointServer s(params());
  s.commit(mmh::test::minJerkTraj(Vector3d(0, 0, 1), Vector3d(2, 0, 1), 2.0), at(0), 1, at(0));
  for (int64_t t = at(0); t <= at(30.0); t += kPeriod) {
    if ((t - kT0) % 1'000'000 == 0) s.arbiterAlive(t);
    EXPECT_NE(s.sample(t)->state, State::kHover);
  }
  EXPECT_FALSE(s.watchdogTripped());
  EXPECT_EQ(s.counters().watchdog_trips, 0);
}

TEST(SetpointServer, TheWatchdogBrakesAlongThePathWithinAmaxToAHover) {
  SetpointServer s(params());
  // 3 m/s along a curve (x line plus a slow sideways drift), far longer than the silence.
  auto traj = mmh::test::line(Vector3d(0, 0, 1), Vector3d(3, 0.3, 0), 30.0);
  s.commit(traj, at(0), 1, at(0));
  s.arbiterAlive(at(1.0));  // the last sign of the planner
  std::optional<Setpoint> previous;
  std::optional<int64_t> tripped_at, hover_at;
  for (int64_t t = at(0); t <= at(10.0); t += kPeriod) {
    const Setpoint sp = *s.sample(t);
    if (!tripped_at && s.watchdogTripped()) tripped_at = t;
    if (!hover_at && sp.state == State::kHover) hover_at = t;
    if (tripped_at) {
      EXPECT_LE(sp.kinematics.acceleration.norm(), 2.0 * (1.0 + 1e-3)) << (t - kT0) * 1e-6;
      ASSERT_TRUE(previous.has_value());
      EXPECT_LE((sp.kinematics.velocity - previous->kinematics.velocity).norm(),
                2.0 * 0.01 * (1.0 + 1e-3));
      EXPECT_LE((sp.kinematics.position - previous->kinematics.position).norm(), 3.1 * 0.01);
    }
    previous = sp;
  }
  ASSERT_TRUE(tripped_at.has_value());
  EXPECT_GT(*tripped_at, at(3.5));  // 2.5 s after the last heartbeat, not before
  EXPECT_LE(*tripped_at, at(3.5) + kPeriod);
  ASSERT_TRUE(hover_at.has_value());
  EXPECT_GE(*hover_at - *tripped_at, 1'400'000);  // 3 m/s at 2 m/s^2 takes 1.5 s
  EXPECT_EQ(previous->state, State::kHover);
  EXPECT_EQ(previous->kinematics.velocity, Vector3d::Zero());
  EXPECT_NE(s.watchdogReason().find("setpoint.watchdog_s"), std::string::npos);
  EXPECT_NE(s.watchdogReason().find("braking to a hover at"), std::string::npos);
  EXPECT_EQ(s.counters().watchdog_trips, 1);
  // A new trajectory from the hover ends the watchdog.
  s.commit(mmh::test::minJerkTraj(previous->kinematics.position,
                                  previous->kinematics.position + Vector3d(1, 0, 0), 2.0),
           at(10.5), 9, at(10.2));
  const Setpoint resumed = *s.sample(at(11.0));
  EXPECT_FALSE(s.watchdogTripped());
  EXPECT_EQ(resumed.state, State::kTracking);
  EXPECT_EQ(resumed.trajectory_id, 9);
  EXPECT_EQ(s.counters().jumps, 0);
}

TEST(SetpointServer, YawTurnsTowardsTheDirectionOfFlightWithinItsRateLimit) {
  SetpointServer s(params());
  s.vehicleAt(Vector3d(0, 0, 1), 0.0);
  s.commit(mmh::test::line(Vector3d(0, 0, 1), Vector3d(0, 2, 0), 10.0), at(0), 1, at(0));
  double yaw = 0.0;
  for (int64_t t = at(0); t <= at(3.0); t += kPeriod) {
    const Setpoint sp = *s.sample(t);
    EXPECT_LE(std::abs(sp.yaw_rate_radps), 90.0 * M_PI / 180.0 + 1e-9);
    yaw = sp.yaw_rad;
  }
  EXPECT_NEAR(yaw, M_PI / 2, 1e-6);  // along +y after 1 s of turning at 90 deg/s
}

TEST(SetpointServer, YawFacesTheWayOfAVehicleCreepingTooSlowlyForTheLookAheadTime) {
  // 0.04 m/s: the point yaw_lookahead_s ahead is 2 cm away, too near to give a direction; the
  // yaw still turns to +y, so the camera looks where the vehicle creeps.
  SetpointServer s(params());
  s.vehicleAt(Vector3d(0, 0, 1), 0.0);
  s.commit(mmh::test::line(Vector3d(0, 0, 1), Vector3d(0, 0.04, 0), 20.0), at(0), 1, at(0));
  double yaw = 0.0;
  for (int64_t t = at(0); t <= at(3.0); t += kPeriod) yaw = s.sample(t)->yaw_rad;
  EXPECT_NEAR(yaw, M_PI / 2, 1e-6);
}
