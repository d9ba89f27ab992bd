// The vehicle follows committed trajectories exactly, switches at their start time, holds
// position without one, and turns its yaw towards the direction of flight within its rate limit.
#include <gtest/gtest.h>

#include <cmath>

#include "mmh/sim/vehicle.hpp"
#include "traj_helpers.hpp"

using Eigen::Vector3d;
using mmh::sim::FlownPart;
using mmh::sim::Vehicle;

namespace {
constexpr int64_t kT0 = 1'000'000'000;
constexpr int64_t kStep = 10'000;

// Commits trajectory 1 (along x at 1 m/s from where the vehicle is) at kT0 and flies 1 s of it.
std::shared_ptr<const mmh::Trajectory> flyOneSecondAlongX(Vehicle& v,
                                                          std::vector<FlownPart>* flown) {
  auto first = mmh::test::line(v.state().position, Vector3d(1, 0, 0), 10.0);
  v.commit(first, kT0, 1);
  for (int i = 1; i <= 100; ++i) v.advance(kT0 + i * kStep, flown);
  return first;
}
}  // namespace

TEST(Vehicle, HoldsPositionWithoutATrajectory) {
  Vehicle v(Vector3d(1, 2, 1.2), 0.3, kT0, mmh::sim::SimParams{});
  std::vector<FlownPart> flown;
  for (int i = 1; i <= 50; ++i) v.advance(kT0 + i * kStep, &flown);
  EXPECT_TRUE(flown.empty());
  EXPECT_EQ(v.state().position, Vector3d(1, 2, 1.2));
  EXPECT_EQ(v.state().velocity, Vector3d::Zero());
  EXPECT_DOUBLE_EQ(v.yaw(), 0.3);
  EXPECT_EQ(v.firstTrajectoryUtime(), -1);
}

TEST(Vehicle, FollowsExactlyFromTheStartTimeAndHoldsAtTheEnd) {
  const Vector3d start(0, 0, 1);
  Vehicle v(start, 0.0, kT0, mmh::sim::SimParams{});
  auto traj = mmh::test::minJerkTraj(start, Vector3d(3, 0, 1), 3.0);
  const int64_t ts = kT0 + 505'000;  // between two steps
  v.commit(traj, ts, 7);
  std::vector<FlownPart> flown;
  for (int i = 1; i <= 400; ++i) {
    flown.clear();
    const int64_t now = kT0 + i * kStep;
    v.advance(now, &flown);
    const double t = (now - ts) * 1e-6;
    if (t < 0) {
      EXPECT_EQ(v.state().position, start);
      EXPECT_TRUE(flown.empty());
    } else if (t <= 3.0) {
      EXPECT_NEAR((v.state().position - traj->position(t)).norm(), 0.0, 1e-12);
      EXPECT_NEAR((v.state().velocity - traj->velocity(t)).norm(), 0.0, 1e-12);
      EXPECT_NEAR((v.state().acceleration - traj->acceleration(t)).norm(), 0.0, 1e-12);
      ASSERT_EQ(flown.size(), 1u);
      EXPECT_NEAR(flown[0].t1, t, 1e-12);
      EXPECT_EQ(v.activeTrajectoryId(), 7);
    } else {
      EXPECT_NEAR((v.state().position - Vector3d(3, 0, 1)).norm(), 0.0, 1e-12);
      EXPECT_EQ(v.state().velocity, Vector3d::Zero());
    }
  }
  EXPECT_EQ(v.firstTrajectoryUtime(), ts);
  EXPECT_EQ(v.jumps(), 0);
}

TEST(Vehicle, SwitchesAtTheNewStartTimeWithoutAJump) {
  Vehicle v(Vector3d(0, 0, 1), 0.0, kT0, mmh::sim::SimParams{});
  std::vector<FlownPart> flown;
  const auto first = flyOneSecondAlongX(v, &flown);
  // The planner sends a new trajectory that starts 0.255 s ahead, where the old one will be.
  const int64_t ts = kT0 + 1'255'000;
  auto second = mmh::test::line(first->position(1.255), Vector3d(0, 1, 0), 5.0);
  v.commit(second, ts, 2);
  flown.clear();
  for (int i = 101; i <= 125; ++i) v.advance(kT0 + i * kStep, &flown);
  EXPECT_EQ(v.activeTrajectoryId(), 1);  // 1.25 s: still the old one
  EXPECT_NEAR((v.state().position - first->position(1.25)).norm(), 0.0, 1e-12);
  flown.clear();
  v.advance(kT0 + 126 * kStep, &flown);  // 1.26 s: switched at 1.255 s
  EXPECT_EQ(v.activeTrajectoryId(), 2);
  ASSERT_EQ(flown.size(), 2u);
  EXPECT_EQ(flown[0].trajectory, first);
  EXPECT_NEAR(flown[0].t0, 1.25, 1e-12);
  EXPECT_NEAR(flown[0].t1, 1.255, 1e-12);
  EXPECT_EQ(flown[1].trajectory, second);
  EXPECT_NEAR(flown[1].t0, 0.0, 1e-12);
  EXPECT_NEAR(flown[1].t1, 0.005, 1e-12);
  EXPECT_NEAR((v.state().position - second->position(0.005)).norm(), 0.0, 1e-12);
  EXPECT_EQ(v.jumps(), 0);
  // A trajectory that starts elsewhere makes the vehicle jump (counted, not hidden).
  v.commit(mmh::test::line(Vector3d(5, 5, 1), Vector3d::Zero(), 1.0), kT0 + 130 * kStep, 3);
  v.advance(kT0 + 131 * kStep, &flown);
  EXPECT_EQ(v.jumps(), 1);
  EXPECT_GT(v.jumpDistance(), 3.0);
}

TEST(Vehicle, ACommitDeliveredAfterItsStartIsTakenOverLateNotCountedAsAJump) {
  Vehicle v(Vector3d(0, 0, 1), 0.0, kT0, mmh::sim::SimParams{});
  std::vector<FlownPart> flown;
  const auto first = flyOneSecondAlongX(v, &flown);
  // Continuous with the old trajectory at 0.95 s, but delivered at 1.0 s: the vehicle is already
  // 5 cm along x, where the new one (along y) is not.
  auto second = mmh::test::line(first->position(0.95), Vector3d(0, 1, 0), 5.0);
  v.commit(second, kT0 + 950'000, 2);
  v.advance(kT0 + 101 * kStep, &flown);
  EXPECT_EQ(v.activeTrajectoryId(), 2);
  EXPECT_EQ(v.jumps(), 0);
  EXPECT_EQ(v.lateTakeovers(), 1);
  EXPECT_NEAR(v.lastLatenessS(), 0.05, 1e-9);
  EXPECT_NEAR(v.lastLateStepM(), std::sqrt(0.05 * 0.05 + 0.05 * 0.05), 1e-9);
  EXPECT_NEAR(v.jumpDistance(), v.lastLateStepM(), 1e-12);
  // Late and discontinuous at its own start: still a jump.
  v.commit(mmh::test::line(Vector3d(5, 5, 1), Vector3d::Zero(), 1.0), kT0 + 1'000'000, 3);
  v.advance(kT0 + 102 * kStep, &flown);
  EXPECT_EQ(v.jumps(), 1);
  EXPECT_EQ(v.lateTakeovers(), 1);
  EXPECT_EQ(v.lostCommits(), 0);
  // Commit 4 lost in transport: 5 continues it, not what the vehicle flies. Counted apart.
  v.commit(mmh::test::line(Vector3d(7, 7, 1), Vector3d::Zero(), 1.0), kT0 + 1'040'000, 5);
  v.advance(kT0 + 105 * kStep, &flown);
  EXPECT_EQ(v.activeTrajectoryId(), 5);
  EXPECT_EQ(v.lostCommits(), 1);
  EXPECT_EQ(v.jumpsAfterLoss(), 1);
  EXPECT_EQ(v.jumps(), 1);
}

TEST(Vehicle, LaterCommitReplacesQueuedOnesAndEmptyMeansHold) {
  const Vector3d start(0, 0, 1);
  Vehicle v(start, 0.0, kT0, mmh::sim::SimParams{});
  v.commit(mmh::test::line(start, Vector3d(1, 0, 0), 10.0), kT0 + 500'000, 1);
  v.commit(mmh::test::line(start, Vector3d(0, 1, 0), 10.0), kT0 + 200'000, 2);  // replaces 1
  std::vector<FlownPart> flown;
  for (int i = 1; i <= 100; ++i) v.advance(kT0 + i * kStep, &flown);
  EXPECT_EQ(v.activeTrajectoryId(), 2);
  EXPECT_NEAR(v.state().position.y(), 0.8, 1e-12);
  // An empty trajectory: hold where the vehicle is at its start time.
  v.commit(std::make_shared<const mmh::Trajectory>(), kT0 + 1'000'000, 3);
  for (int i = 101; i <= 150; ++i) v.advance(kT0 + i * kStep, &flown);
  EXPECT_FALSE(v.hasTrajectory());
  EXPECT_NEAR(v.state().position.y(), 0.8, 1e-12);
  EXPECT_EQ(v.state().velocity, Vector3d::Zero());
  // A late trajectory (start in the past) is taken over at the next step, partway.
  auto late = mmh::test::line(Vector3d(0, 0.8, 1), Vector3d(1, 0, 0), 10.0);
  v.commit(late, kT0 + 1'400'000, 4);
  v.advance(kT0 + 151 * kStep, &flown);
  EXPECT_NEAR((v.state().position - late->position(0.11)).norm(), 0.0, 1e-12);
}

TEST(Vehicle, YawTurnsTowardsTheFlightDirectionWithinTheRateLimit) {
  mmh::sim::SimParams params;
  params.max_yaw_rate_dps = 90.0;
  const Vector3d start(0, 0, 1);
  Vehicle v(start, 0.0, kT0, params);
  v.commit(mmh::test::line(start, Vector3d(0, 1, 0), 10.0), kT0, 1);  // fly along +y
  std::vector<FlownPart> flown;
  double previous = v.yaw();
  for (int i = 1; i <= 300; ++i) {
    v.advance(kT0 + i * kStep, &flown);
    EXPECT_LE(std::abs(v.yaw() - previous), 90.0 * M_PI / 180.0 * 0.01 + 1e-12);
    previous = v.yaw();
  }
  EXPECT_NEAR(v.yaw(), M_PI / 2, 1e-3);
  const Eigen::Quaterniond q = v.orientation();
  EXPECT_NEAR((q * Vector3d::UnitX() - Vector3d::UnitY()).norm(), 0.0, 1e-3);
}

TEST(Vehicle, YawFacesTheWayOfACreepWhoseLookAheadPointIsTooNear) {
  // At 0.05 m/s the point yaw_lookahead_s ahead is 2.5 cm away: too near to show a direction.
  // The camera must still turn to where the vehicle goes, or it creeps into what it never saw.
  const Vector3d start(0, 0, 1);
  mmh::sim::SimParams params;
  Vehicle creeping(start, 0.0, kT0, params);
  params.yaw_lookahead_min_m = 0.0;
  Vehicle looking_only_by_time(start, 0.0, kT0, params);
  const auto creep = mmh::test::line(start, Vector3d(0, 0.05, 0), 20.0);
  creeping.commit(creep, kT0, 1);
  looking_only_by_time.commit(creep, kT0, 1);
  std::vector<FlownPart> flown;
  for (int i = 1; i <= 300; ++i) {
    creeping.advance(kT0 + i * kStep, &flown);
    looking_only_by_time.advance(kT0 + i * kStep, &flown);
  }
  EXPECT_NEAR(creeping.yaw(), M_PI / 2, 1e-3);
  EXPECT_DOUBLE_EQ(looking_only_by_time.yaw(), 0.0);
}
