// The arbiter's rules one by one, with scripted inputs (no LCM, no planners).
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>

#include "../sim/traj_helpers.hpp"
#include "mmh/arbiter/arbiter.hpp"
#include "mmh/arbiter/local_target.hpp"
#include "mmh/common/collision_check.hpp"
#include "mmh/common/minco.hpp"
#include "mmh/common/stopping_trajectory.hpp"

using Eigen::Vector3d;
using Eigen::Vector3i;
using mmh::KinematicState;
using mmh::Trajectory;
using namespace mmh::arbiter;

namespace {

constexpr int64_t kT0 = 1'000'000'000;  // message clock at the start of each test
int64_t at(double seconds) {
  return kT0 + static_cast<int64_t>(seconds * 1e6);
}

// A feasible rest-ending quintic from `start` to `target` (what a simple mode could answer).
Trajectory simplePlan(const KinematicState& start, const Vector3d& target) {
  for (double T = 0.8 * (target - start.position).norm() + 1.0;; T *= 1.1) {
    Trajectory t = mmh::test::planFrom(start, target, T);
    if (t.maxSpeed() <= 3.0 && t.maxAcceleration() <= 2.0) return t;
  }
}

class ArbiterRules : public ::testing::Test {
 protected:
  ArbiterRules() {
    params_.geofence_min_m = Vector3d(-30, -30, 0.3);
    params_.geofence_max_m = Vector3d(30, 30, 2.7);
    clearGrid();
  }

  // An empty, fully mapped window around the origin.
  void clearGrid() {
    grid_ = mmh::VoxelGrid(0.1, Vector3i(-160, -160, -8), Vector3i(320, 320, 40));
    grid_.setInflationRadius(params_.check_inflation_m);
    for (int64_t i = 0; i < grid_.numCells(); ++i) grid_.setLinear(i, mmh::Occupancy::kFree);
  }

  // Goal, map, awareness and odometry at rest at the origin: the arbiter's first request.
  std::unique_ptr<Arbiter> started(Policy policy, bool safe = true) {
    params_.policy = policy;
    auto a = std::make_unique<Arbiter>(params_);
    a->onMapUpdated(grid_, ++map_seq_, at(0), at(0));
    a->setAwareness(safe, safe ? 0 : 1, 1, map_seq_);
    std::string why;
    EXPECT_TRUE(a->setGoal(1, goal_, at(0), &why)) << why;
    a->onOdometry(rest(Vector3d(0, 0, 1.2)), at(0));
    return a;
  }

  static KinematicState rest(const Vector3d& p) {
    KinematicState s;
    s.position = p;
    return s;
  }

  static ModeAnswer okAnswer(const PlanRequestOut& r) {
    ModeAnswer a;
    a.request_id = r.request_id;
    a.mode = r.mode;
    a.ok = true;
    a.compute_us = 100;
    a.start_utime = r.start_utime;
    a.trajectory = simplePlan(r.start, r.target);
    return a;
  }

  static ModeAnswer failedAnswer(const PlanRequestOut& r) {
    ModeAnswer a;
    a.request_id = r.request_id;
    a.mode = r.mode;
    a.ok = false;
    a.reason = 6;
    a.detail = "no path";
    return a;
  }

  // Flies the committed trajectory with odometry at 100 Hz from `from` to `to` (seconds), with a
  // fresh map every 0.1 s unless told otherwise; returns the requests that appeared.
  std::vector<PlanRequestOut> fly(Arbiter& a, double from, double to, bool maps = true) {
    std::vector<PlanRequestOut> all;
    for (double t = from; t <= to + 1e-9; t += 0.01) {
      const int64_t now = at(t);
      if (maps && std::lround(t * 100) % 10 == 0) a.onMapUpdated(grid_, ++map_seq_, now, now);
      KinematicState s = a.committed().state((now - a.committedStartUtime()) * 1e-6);
      a.onOdometry(s, now);
      for (auto& r : a.takeRequests()) all.push_back(r);
      if (!all.empty()) return all;
    }
    return all;
  }

  // Commits the first answer and flies it (fly) to just before its halfway point, where the
  // vehicle is fast; returns that time in seconds and the committed state there in *state.
  double flyToCruise(Arbiter& a, KinematicState* state) {
    auto r = a.takeRequests().at(0);
    a.onAnswer(okAnswer(r), at(0.001));
    EXPECT_TRUE(a.takeCommit());
    const double t1 = std::floor(0.45 * a.committed().duration() * 10.0) / 10.0;
    EXPECT_TRUE(fly(a, 0.01, t1).empty());
    *state = a.committed().state((at(t1) - a.committedStartUtime()) * 1e-6);
    EXPECT_GT(state->velocity.norm(), 1.0);
    return t1;
  }

  // Flown to cruise speed (flyToCruise), then a map at that time shows a pillar `ahead_m` ahead of
  // the vehicle on the committed trajectory; returns that time in seconds.
  double cruiseIntoMappedPillar(Arbiter& a, double ahead_m, KinematicState* before) {
    const double t1 = flyToCruise(a, before);
    putPillar(before->position.x() + ahead_m, 0.0, 0.4);
    a.onMapUpdated(grid_, ++map_seq_, at(t1), at(t1));
    return t1;
  }

  // Never making progress (no step toward the goal is ever large enough: stuck once a round
  // fails), flown to cruise speed with a pillar 2.5 m ahead, not yet on the map; *t1 the time.
  std::unique_ptr<Arbiter> stuckBeforeAPillar(double* t1) {
    params_.progress_min_step_m = 1000.0;
    params_.progress_new_ground_m = 0.0;  // flying on is no progress either
    params_.stuck_after_s = 0.5;
    auto a = started(Policy::kMmh);
    KinematicState before;
    *t1 = flyToCruise(*a, &before);
    putPillar(before.position.x() + 2.5, 0.0, 0.4);
    return a;
  }

  // Flown to cruise speed, a pillar mapped 7 m ahead on the committed trajectory, and EAM,
  // asked at once, fails: a round where every mode failed with the danger far. *path and
  // *path_start: what was committed before; returns the time of that map in seconds.
  double failARoundBeforeAFarPillar(Arbiter& a, Trajectory* path, int64_t* path_start) {
    KinematicState before;
    const double t1 = cruiseIntoMappedPillar(a, 7.0, &before);
    *path = a.committed();
    *path_start = a.committedStartUtime();
    auto eam = a.takeRequests();
    EXPECT_EQ(eam.size(), 1u);
    a.takeDecisions();
    if (!eam.empty()) a.onAnswer(failedAnswer(eam[0]), at(t1 + 0.005));
    return t1;
  }

  // The largest distance of `traj` (sampled every 0.05 s) from `path` flown from s0 seconds on.
  static double farthestFromPath(const Trajectory& traj, const Trajectory& path, double s0) {
    double farthest = 0.0;
    for (double t = 0.0; t <= traj.duration(); t += 0.05) {
      double nearest = 1e9;
      for (double u = s0; u <= path.duration(); u += 0.002)
        nearest = std::min(nearest, (path.position(u) - traj.position(t)).norm());
      farthest = std::max(farthest, nearest);
    }
    return farthest;
  }

  // With `above`, a fence whose ceiling lies 3 cm below the start (1.2 m) and a goal under it:
  // the vehicle flies 1-3 cm above the fence, within the tolerance answers are accepted with (so
  // an accepted answer may leave it there). Else the fixture's fence and goal.
  void setCeilingJustBelowTheVehicle(bool above) {
    params_.geofence_max_m.z() = above ? 1.17 : 2.7;
    goal_.z() = above ? 1.15 : 1.2;
    // The test's first plan (0.8 s per metre) is not a slow one to be replanned at once.
    params_.slow_plan_ratio = above ? 3.0 : ArbiterParams{}.slow_plan_ratio;
  }

  void putPillar(double x, double y, double radius) {
    for (int64_t i = 0; i < grid_.numCells(); ++i) {
      const Vector3d c = grid_.centerOfLocal(grid_.localFromLinear(i));
      if (std::hypot(c.x() - x, c.y() - y) <= radius) grid_.setLinear(i, mmh::Occupancy::kOccupied);
    }
  }

  ArbiterParams params_;
  mmh::VoxelGrid grid_;
  int64_t map_seq_ = 0;
  Vector3d goal_{28.0, 0.0, 1.2};
};

}  // namespace

TEST_F(ArbiterRules, SafeAwarenessAsksFpmAndCommitsAContinuousAnswer) {
  auto a = started(Policy::kMmh, true);
  auto requests = a->takeRequests();
  ASSERT_EQ(requests.size(), 1u);
  const PlanRequestOut r = requests[0];
  EXPECT_EQ(r.mode, Mode::kFpm);
  EXPECT_EQ(r.trigger, Trigger::kInitial);
  EXPECT_EQ(r.start_utime, at(params_.replan_lead_s));
  // Local target: the planning range (5 s at 3 m/s) towards the goal.
  EXPECT_TRUE(r.target.isApprox(Vector3d(15, 0, 1.2)));
  a->onAnswer(okAnswer(r), at(0.001));
  auto commit = a->takeCommit();
  ASSERT_TRUE(commit.has_value());
  EXPECT_EQ(commit->start_utime, r.start_utime);
  EXPECT_EQ(commit->mode, Mode::kFpm);
  auto decisions = a->takeDecisions();
  ASSERT_FALSE(decisions.empty());
  EXPECT_EQ(decisions.back().outcome, Outcome::kCommitted);
  EXPECT_EQ(a->counters().iterations[1], 1);
}

TEST_F(ArbiterRules, UnsafeAwarenessAsksSom) {
  auto a = started(Policy::kMmh, false);
  auto requests = a->takeRequests();
  ASSERT_EQ(requests.size(), 1u);
  EXPECT_EQ(requests[0].mode, Mode::kSom);
}

TEST_F(ArbiterRules, ReplansOnlyPastTheHalfwayPointFromTheCommittedState) {
  auto a = started(Policy::kMmh);
  auto r = a->takeRequests().at(0);
  a->onAnswer(okAnswer(r), at(0.001));
  ASSERT_TRUE(a->takeCommit());
  const double duration = a->committed().duration();
  // Nothing before the halfway point (lazy: never on a timer)...
  auto early = fly(*a, 0.01, 0.5 * duration - 0.05);
  EXPECT_TRUE(early.empty());
  // ...then a halfway replan whose start state is the committed trajectory's state at its start.
  auto later = fly(*a, 0.5 * duration - 0.04, 0.5 * duration + 0.1);
  ASSERT_EQ(later.size(), 1u);
  EXPECT_EQ(later[0].trigger, Trigger::kHalfway);
  const KinematicState expected =
      a->committed().state((later[0].start_utime - a->committedStartUtime()) * 1e-6);
  EXPECT_LT((later[0].start.position - expected.position).norm(), 1e-12);
  EXPECT_LT((later[0].start.velocity - expected.velocity).norm(), 1e-12);
  EXPECT_LT((later[0].start.acceleration - expected.acceleration).norm(), 1e-12);
  // The new local target is again the planning range ahead of the start, or at the map
  // window's face (0.5 m inside) when that comes first.
  const double expected_x = std::min(later[0].start.position.x() + 15.0, 16.0 - 0.5);
  EXPECT_NEAR(later[0].target.x(), expected_x, 1e-6);
  EXPECT_NEAR(later[0].target.y(), 0.0, 1e-6);
}

TEST_F(ArbiterRules, AHalfwayAnswerThatWouldArriveLaterIsNotTakenAndTheRestIsReplannedLater) {
  auto a = started(Policy::kMmh);
  auto r = a->takeRequests().at(0);
  a->onAnswer(okAnswer(r), at(0.001));
  auto plan = a->takeCommit();
  ASSERT_TRUE(plan.has_value());
  const double duration = plan->trajectory.duration();
  auto halfway = fly(*a, 0.01, 0.5 * duration + 0.1);
  ASSERT_EQ(halfway.size(), 1u);
  ASSERT_EQ(halfway[0].trigger, Trigger::kHalfway);
  a->takeDecisions();
  // A loop: out to the side and back, then to the target - seconds later than the committed rest.
  ModeAnswer loop = okAnswer(halfway[0]);
  KinematicState aside = rest(halfway[0].start.position + Vector3d(0.0, 6.0, 0.0));
  Trajectory out = mmh::test::planFrom(halfway[0].start, aside.position, 6.0);
  Trajectory back = simplePlan(aside, halfway[0].target);
  for (const auto& piece : back.pieces()) out.append(piece);
  loop.trajectory = out;
  const int64_t asked = at(0.5 * duration + 0.1);
  a->onAnswer(loop, asked);
  EXPECT_FALSE(a->takeCommit().has_value());  // the committed trajectory flies on
  auto decisions = a->takeDecisions();
  ASSERT_EQ(decisions.size(), 1u);
  EXPECT_EQ(decisions[0].outcome, Outcome::kKept);
  EXPECT_EQ(decisions[0].committed_mode, plan->mode);
  EXPECT_NE(decisions[0].detail.find("kept, replanning in"), std::string::npos)
      << decisions[0].detail;
  EXPECT_EQ(a->counters().kept_trajectories, 1);
  EXPECT_EQ(a->committedStartUtime(), plan->start_utime);
  // No new round at once; the next halfway replan comes halfway through the rest.
  const double start_s = (halfway[0].start_utime - plan->start_utime) * 1e-6;
  const double next_s = start_s + 0.5 * (duration - start_s);
  const double from_s = (asked - kT0) * 1e-6 + 0.01;
  EXPECT_TRUE(fly(*a, from_s, next_s - 0.05).empty());
  auto next = fly(*a, next_s - 0.04, next_s + 0.1);
  ASSERT_EQ(next.size(), 1u);
  EXPECT_EQ(next[0].trigger, Trigger::kHalfway);
  // An answer no later than the committed rest is taken.
  a->onAnswer(okAnswer(next[0]), at(next_s + 0.11));
  EXPECT_TRUE(a->takeCommit().has_value());
}

TEST_F(ArbiterRules, NoHalfwayReplanWhenTheTrajectoryEndsAtTheGoal) {
  goal_ = Vector3d(8.0, 0.0, 1.2);
  auto a = started(Policy::kMmh);
  auto r = a->takeRequests().at(0);
  EXPECT_TRUE(r.target.isApprox(goal_));
  a->onAnswer(okAnswer(r), at(0.001));
  ASSERT_TRUE(a->takeCommit());
  EXPECT_TRUE(fly(*a, 0.01, a->committed().duration() + 0.2).empty());
  auto decisions = a->takeDecisions();
  ASSERT_FALSE(decisions.empty());
  EXPECT_EQ(decisions.back().outcome, Outcome::kReached);
  EXPECT_TRUE(a->reached());
}

TEST_F(ArbiterRules, NewObstacleOnTheCommittedTrajectoryAsksEamWithTheReference) {
  params_.emergency_horizon_s = 30.0;  // every collision is an emergency
  auto a = started(Policy::kMmh);
  auto r = a->takeRequests().at(0);
  a->onAnswer(okAnswer(r), at(0.001));
  ASSERT_TRUE(a->takeCommit());
  fly(*a, 0.01, 1.0);
  putPillar(9.0, 0.0, 0.4);  // across the committed straight line
  a->onMapUpdated(grid_, ++map_seq_, at(1.0), at(1.0));
  auto requests = a->takeRequests();
  ASSERT_EQ(requests.size(), 1u);
  EXPECT_EQ(requests[0].mode, Mode::kEam);
  EXPECT_EQ(requests[0].trigger, Trigger::kCollision);
  ASSERT_FALSE(requests[0].reference.empty());
  // The reference is the rest of the committed trajectory from the new start time.
  EXPECT_LT((requests[0].reference.position(0) - requests[0].start.position).norm(), 1e-9);
  EXPECT_TRUE(requests[0].target.isApprox(a->committed().position(a->committed().duration())));
}

TEST_F(ArbiterRules, ACollisionRepairKeepsTheHalfwayPointOfThePlanItRepairs) {
  params_.emergency_horizon_s = 30.0;  // every collision is an emergency: EAM with the reference
  auto a = started(Policy::kMmh);
  auto r = a->takeRequests().at(0);
  a->onAnswer(okAnswer(r), at(0.001));
  auto plan = a->takeCommit();
  ASSERT_TRUE(plan.has_value());
  const int64_t plan_halfway =
      plan->start_utime + static_cast<int64_t>(0.5 * plan->trajectory.duration() * 1e6);
  ASSERT_TRUE(fly(*a, 0.01, 1.0).empty());
  putPillar(9.0, 0.0, 0.4);
  a->onMapUpdated(grid_, ++map_seq_, at(1.0), at(1.0));
  auto repair_request = a->takeRequests();
  ASSERT_EQ(repair_request.size(), 1u);
  ASSERT_FALSE(repair_request[0].reference.empty());
  // The pillar was a false return; the repair (same end, its own timing) is committed.
  for (int64_t i = 0; i < grid_.numCells(); ++i) grid_.setLinear(i, mmh::Occupancy::kFree);
  a->onAnswer(okAnswer(repair_request[0]), at(1.001));
  auto repair = a->takeCommit();
  ASSERT_TRUE(repair.has_value());
  const int64_t own_halfway =
      repair->start_utime + static_cast<int64_t>(0.5 * repair->trajectory.duration() * 1e6);
  ASSERT_GT(own_halfway, plan_halfway + 200'000) << "the test needs a repair slower than the plan";
  // The halfway replan comes at the repaired plan's halfway point, not the repair's own.
  const double from_s = (repair->start_utime - kT0) * 1e-6;
  auto next = fly(*a, from_s, (own_halfway - kT0) * 1e-6);
  ASSERT_EQ(next.size(), 1u);
  EXPECT_EQ(next[0].trigger, Trigger::kHalfway);
  const int64_t asked_at = next[0].start_utime - static_cast<int64_t>(params_.replan_lead_s * 1e6);
  EXPECT_GE(asked_at, plan_halfway);
  EXPECT_LE(asked_at, plan_halfway + 20'000);
}

TEST_F(ArbiterRules, CollisionBeyondTheEmergencyHorizonAsksTheAwarenessMode) {
  params_.emergency_horizon_s = 0.5;
  auto a = started(Policy::kMmh, /*safe=*/false);
  auto r = a->takeRequests().at(0);
  ASSERT_EQ(r.mode, Mode::kSom);
  a->onAnswer(okAnswer(r), at(0.001));
  ASSERT_TRUE(a->takeCommit());
  fly(*a, 0.01, 1.0);
  putPillar(9.0, 0.0, 0.4);  // seconds ahead of the vehicle
  a->onMapUpdated(grid_, ++map_seq_, at(1.0), at(1.0));
  auto requests = a->takeRequests();
  ASSERT_EQ(requests.size(), 1u);
  EXPECT_EQ(requests[0].trigger, Trigger::kCollision);
  EXPECT_EQ(requests[0].mode, Mode::kSom);
  EXPECT_TRUE(requests[0].reference.empty());
}

TEST_F(ArbiterRules, FarCollisionsAreLeftToTheHalfwayReplan) {
  auto lazy = started(Policy::kMmh);
  lazy->onAnswer(okAnswer(lazy->takeRequests().at(0)), at(0.001));
  ASSERT_TRUE(lazy->takeCommit());
  params_.defer_far_collisions = false;
  auto eager = started(Policy::kMmh);
  eager->onAnswer(okAnswer(eager->takeRequests().at(0)), at(0.001));
  ASSERT_TRUE(eager->takeCommit());
  putPillar(13.5, 0.0, 0.3);  // near the end of the committed trajectories, far beyond halfway
  lazy->onMapUpdated(grid_, ++map_seq_, at(0.5), at(0.5));
  eager->onMapUpdated(grid_, map_seq_, at(0.5), at(0.5));
  EXPECT_TRUE(lazy->takeRequests().empty());
  auto now = eager->takeRequests();  // without the deferral: EAM at once
  ASSERT_EQ(now.size(), 1u);
  EXPECT_EQ(now[0].trigger, Trigger::kCollision);
  // The halfway replan comes first and plans with the map that has the pillar.
  auto later = fly(*lazy, 0.51, lazy->committed().duration());
  ASSERT_EQ(later.size(), 1u);
  EXPECT_EQ(later[0].trigger, Trigger::kHalfway);
}

TEST_F(ArbiterRules, SomFailureFallsBackToEam) {
  auto a = started(Policy::kMmh, false);
  auto r = a->takeRequests().at(0);
  ASSERT_EQ(r.mode, Mode::kSom);
  a->onAnswer(failedAnswer(r), at(0.001));
  EXPECT_FALSE(a->takeCommit().has_value());
  auto decisions = a->takeDecisions();
  ASSERT_FALSE(decisions.empty());
  EXPECT_EQ(decisions.back().outcome, Outcome::kFailed);
  a->onOdometry(rest(Vector3d(0, 0, 1.2)), at(0.01));
  auto retry = a->takeRequests();
  ASSERT_EQ(retry.size(), 1u);
  EXPECT_EQ(retry[0].mode, Mode::kEam);
  EXPECT_EQ(retry[0].trigger, Trigger::kRetry);
  // Both failed: no spinning until the map changes.
  a->onAnswer(failedAnswer(retry[0]), at(0.011));
  a->onOdometry(rest(Vector3d(0, 0, 1.2)), at(0.02));
  EXPECT_TRUE(a->takeRequests().empty());
  a->onMapUpdated(grid_, ++map_seq_, at(0.05), at(0.05));
  auto again = a->takeRequests();
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].mode, Mode::kSom);
}

TEST_F(ArbiterRules, NoAnswerByTheDeadlineWithDangerAheadCommitsAStop) {
  auto a = started(Policy::kMmh);
  KinematicState before;
  // Near enough that a stop begun stop_decision_margin_s later would reach it.
  const double t1 = cruiseIntoMappedPillar(*a, 2.5, &before);
  auto eam = a->takeRequests();
  ASSERT_EQ(eam.size(), 1u);
  // EAM never answers; time passes beyond the deadline.
  const double deadline = t1 + params_.answer_deadline_s + 0.01;
  KinematicState s = a->committed().state((at(deadline) - a->committedStartUtime()) * 1e-6);
  a->onOdometry(s, at(deadline));
  auto commit = a->takeCommit();
  ASSERT_TRUE(commit.has_value());
  EXPECT_EQ(commit->mode, Mode::kStop);
  auto decisions = a->takeDecisions();
  ASSERT_FALSE(decisions.empty());
  EXPECT_EQ(decisions.back().outcome, Outcome::kStopping);
  EXPECT_EQ(a->counters().unanswered, 1);
  // The stop continues the old trajectory without a jump and ends at rest within the limits.
  const Trajectory& stop = commit->trajectory;
  EXPECT_LT((stop.state(0).velocity - s.velocity).norm(), 0.05);  // s is 10 ms earlier
  EXPECT_LT(stop.velocity(stop.duration()).norm(), 1e-6);
  EXPECT_LE(stop.maxAcceleration(), params_.max_acc_mps2 + 1e-9);
}

TEST_F(ArbiterRules, TheAnswerToANewlyMappedDangerNamesWhenTheMapShowedIt) {
  params_.emergency_horizon_s = 30.0;  // every collision is an emergency: EAM
  auto a = started(Policy::kMmh);
  KinematicState before;
  const double t1 = flyToCruise(*a, &before);
  a->takeDecisions();
  // The map of a scan taken 30 ms ago shows a pillar on the committed trajectory.
  putPillar(before.position.x() + 4.0, 0.0, 0.4);
  a->onMapUpdated(grid_, ++map_seq_, at(t1 - 0.03), at(t1));
  auto eam = a->takeRequests();
  ASSERT_EQ(eam.size(), 1u);
  // EAM answers with a stop short of the pillar: committed, naming the scan's time.
  ModeAnswer answer = okAnswer(eam[0]);
  answer.trajectory = simplePlan(eam[0].start, eam[0].start.position + Vector3d(2.0, 0, 0));
  a->onAnswer(answer, at(t1 + 0.005));
  ASSERT_TRUE(a->takeCommit());
  auto decisions = a->takeDecisions();
  ASSERT_EQ(decisions.size(), 1u);
  EXPECT_EQ(decisions[0].outcome, Outcome::kCommitted) << decisions[0].detail;
  EXPECT_EQ(decisions[0].threat_seen_utime, at(t1 - 0.03));
  // Decisions that answer no new danger name none.
  EXPECT_TRUE(fly(*a, t1 + 0.01, t1 + 0.3).empty());
  a->onAnswer(okAnswer(eam[0]), at(t1 + 0.31));  // a duplicate: ignored
  for (const DecisionOut& d : a->takeDecisions()) EXPECT_EQ(d.threat_seen_utime, 0);
}

TEST_F(ArbiterRules, AStopAfterAFailedRoundAnswersTheDangerThatRoundWasFor) {
  auto a = started(Policy::kMmh);
  KinematicState before;
  const double t1 = flyToCruise(*a, &before);
  a->takeDecisions();
  putPillar(before.position.x() + 2.5, 0.0, 0.4);
  a->onMapUpdated(grid_, ++map_seq_, at(t1 - 0.02), at(t1));
  auto eam = a->takeRequests();
  ASSERT_EQ(eam.size(), 1u);
  a->onAnswer(failedAnswer(eam[0]), at(t1 + 0.005));
  auto decisions = a->takeDecisions();
  ASSERT_FALSE(decisions.empty());
  EXPECT_EQ(decisions.front().outcome, Outcome::kFailed);
  EXPECT_EQ(decisions.front().threat_seen_utime, 0);  // not answered yet
  // The stop (now, or after the fallback fails too) answers it.
  for (int i = 0; i < 5 && decisions.back().outcome != Outcome::kStopping; ++i) {
    for (auto& r : fly(*a, t1 + 0.01 * (i + 1), t1 + 0.01 * (i + 1))) {
      a->onAnswer(failedAnswer(r), at(t1 + 0.01 * (i + 1) + 0.001));
    }
    for (auto& d : a->takeDecisions()) decisions.push_back(d);
  }
  ASSERT_EQ(decisions.back().outcome, Outcome::kStopping);
  EXPECT_EQ(decisions.back().threat_seen_utime, at(t1 - 0.02));
}

TEST_F(ArbiterRules, AnObstacleMappedOnABrakingStopIsAnsweredOnThatMap) {
  // A pillar beside the stop's way; a wall across it: none of the stops that swerve is clear of
  // the wall; a pillar on the stop's way while the arbiter asks a clearance that no stop keeps
  // from it (the map's inflation unchanged): only a stop that keeps the airframe off it helps.
  enum class Blocker { kPillarBeside, kWallAcross, kPillarOnTheWay };
  for (const Blocker blocker :
       {Blocker::kPillarBeside, Blocker::kWallAcross, Blocker::kPillarOnTheWay}) {
    SCOPED_TRACE(static_cast<int>(blocker));
    const bool wall = blocker == Blocker::kWallAcross;
    const bool no_clear_stop = blocker == Blocker::kPillarOnTheWay;
    clearGrid();
    params_.check_inflation_m = no_clear_stop ? 1.2 : ArbiterParams{}.check_inflation_m;
    auto a = started(Policy::kMmh);
    KinematicState before;
    const double t1 = cruiseIntoMappedPillar(*a, 2.5, &before);
    // Every mode fails: the vehicle brakes in a stop.
    std::optional<CommitOut> stop;
    double t = t1;
    for (auto requests = a->takeRequests(); !stop && t < t1 + 1.0;) {
      for (auto& r : requests) a->onAnswer(failedAnswer(r), at(t + 0.001));
      stop = a->takeCommit();
      t += 0.01;
      if (!stop) requests = fly(*a, t, t);
    }
    ASSERT_TRUE(stop.has_value());
    ASSERT_EQ(stop->mode, Mode::kStop);
    a->takeDecisions();
    // A map 50 ms later shows an obstacle on the stop's own way, well within the retry period.
    ASSERT_LT(0.1, params_.stop_retry_period_s);
    const Trajectory& braking = stop->trajectory;
    const Vector3d ahead = braking.position(0.6 * braking.duration());
    if (wall) {
      for (double y = -4.0; y <= 4.0; y += 0.1) putPillar(ahead.x(), y, 0.1);
    } else if (no_clear_stop) {
      // Alone on the map (the first pillar, which every stop passes near, gone), where the stop
      // under way ends: far enough ahead to swerve from.
      for (int64_t i = 0; i < grid_.numCells(); ++i) grid_.setLinear(i, mmh::Occupancy::kFree);
      const Vector3d end = braking.position(braking.duration());
      putPillar(end.x(), end.y(), 0.071);
    } else {
      putPillar(ahead.x(), ahead.y() + 0.3, 0.2);
    }
    const double t2 = t + 0.05;
    const int64_t now = at(t2);
    const double elapsed = (now - stop->start_utime) * 1e-6;
    ASSERT_TRUE(mmh::firstCollisionTime(grid_, braking, elapsed, braking.duration()));
    a->onOdometry(braking.state(elapsed), now);
    a->onMapUpdated(grid_, ++map_seq_, now, now);
    // Only an evasive plan can help: a round on this map, not after the retry period, and with
    // EAM, the emergency mode, first (SOM from a hard-braking state rarely keeps the limits).
    auto round = a->takeRequests();
    ASSERT_EQ(round.size(), 1u);
    EXPECT_EQ(round[0].mode, Mode::kEam);
    // It fails: a stop that swerves round the pillar is committed at once, on this map.
    a->onAnswer(failedAnswer(round[0]), now + 1000);
    auto swerve = a->takeCommit();
    if (wall) {
      EXPECT_FALSE(swerve.has_value());  // nothing clear to commit: the modes go on trying
      EXPECT_EQ(a->counters().swerving_stops, 0);
      continue;
    }
    ASSERT_TRUE(swerve.has_value());
    EXPECT_EQ(swerve->mode, Mode::kStop);
    EXPECT_EQ(a->counters().swerving_stops, 1);
    EXPECT_EQ(a->counters().last_resort_stops, no_clear_stop ? 1 : 0);
    const Trajectory& st = swerve->trajectory;
    EXPECT_EQ(mmh::isClearStop(grid_, st, params_.check_inflation_m), !no_clear_stop);
    if (!no_clear_stop) {
      EXPECT_FALSE(mmh::firstCollisionTime(grid_, st, 0.0, st.duration()).has_value());
    }
    const double touch_m = params_.vehicle_radius_m + 0.5 * grid_.resolution();
    EXPECT_GE(mmh::minOccupiedDistance(grid_, st, 1.0), touch_m);
    if (no_clear_stop) {
      const double t0 = (swerve->start_utime - stop->start_utime) * 1e-6;
      EXPECT_LT(mmh::minOccupiedDistance(grid_, braking.tail(t0), 1.0), touch_m);
    }
    const KinematicState from = braking.state((swerve->start_utime - stop->start_utime) * 1e-6);
    EXPECT_LT((st.position(0.0) - from.position).norm(), 1e-6);
    EXPECT_LT((st.velocity(0.0) - from.velocity).norm(), 1e-6);
    EXPECT_LT(st.velocity(st.duration()).norm(), 1e-6);
    EXPECT_LE(st.maxAcceleration(), params_.max_acc_mps2 * 1.001);
    const auto decisions = a->takeDecisions();
    ASSERT_FALSE(decisions.empty());
    EXPECT_EQ(decisions.back().outcome, Outcome::kStopping);
    EXPECT_NE(decisions.back().detail.find(no_clear_stop ? "keeps the airframe off" : "swerving"),
              std::string::npos)
        << decisions.back().detail;
    EXPECT_EQ(decisions.back().threat_seen_utime, now);  // the danger's answer, on its own map
    if (!no_clear_stop) continue;
    // Under way, it is not replaced again on the next maps, where it still comes within the
    // margin: the modes go on trying (and fail).
    int failed_rounds = 0;
    for (double tf = t2 + 0.01; tf < t2 + 0.5; tf += 0.01) {
      for (auto& r : fly(*a, tf, tf)) {
        a->onAnswer(failedAnswer(r), at(tf + 0.001));
        ++failed_rounds;
      }
      EXPECT_FALSE(a->takeCommit().has_value());
    }
    EXPECT_GT(failed_rounds, 0);
    EXPECT_EQ(a->counters().last_resort_stops, 1);
  }
}

TEST_F(ArbiterRules, ADangerThatANewMapNoLongerShowsIsAnsweredByNoLaterCommit) {
  params_.stale_map_s = 10.0;
  params_.failed_round_speed_ratio = 1.0;  // no slowdown answers the danger meanwhile
  params_.backup_stop = false;             // nor a backup stop
  params_.emergency_horizon_s = 30.0;      // every collision is an emergency: EAM
  params_.defer_far_collisions = false;
  auto a = started(Policy::kMmh);
  KinematicState before;
  // A far pillar on the committed trajectory: EAM fails, then SOM; the stop may wait.
  const double t1 = cruiseIntoMappedPillar(*a, 7.0, &before);
  a->takeDecisions();
  int failed = 0;
  auto requests = a->takeRequests();
  for (double t = t1 + 0.01; t < t1 + 0.045; t += 0.01) {
    for (auto& r : requests) {
      a->onAnswer(failedAnswer(r), at(t - 0.005));
      ++failed;
    }
    requests = fly(*a, t, t, false);
  }
  ASSERT_EQ(failed, 2);
  ASSERT_FALSE(a->takeCommit().has_value());
  // The next map shows no pillar (it was noise): the danger is gone.
  for (int64_t i = 0; i < grid_.numCells(); ++i) grid_.setLinear(i, mmh::Occupancy::kFree);
  a->onMapUpdated(grid_, ++map_seq_, at(t1 + 0.05), at(t1 + 0.05));
  // The next commit (a retry from the new map) answers no danger.
  double t = t1 + 0.05;
  auto retry = a->takeRequests();
  while (retry.empty() && t < t1 + 2.0) {
    t += 0.01;
    retry = fly(*a, t, t);
  }
  ASSERT_FALSE(retry.empty());
  a->onAnswer(okAnswer(retry[0]), at(t + 0.001));
  ASSERT_TRUE(a->takeCommit().has_value());
  const auto decisions = a->takeDecisions();
  ASSERT_FALSE(decisions.empty());
  EXPECT_EQ(decisions.back().outcome, Outcome::kCommitted) << decisions.back().detail;
  EXPECT_EQ(decisions.back().threat_seen_utime, 0);
}

TEST_F(ArbiterRules, AFarDangerLetsTheStopWaitUntilItCannotWaitAnyLonger) {
  params_.stale_map_s = 10.0;  // no new maps in this test, and no stale-map stop either
  params_.defer_far_collisions = false;
  params_.failed_round_speed_ratio = 1.0;  // the stop rule alone (the slowdown: its own test)
  params_.backup_stop = false;             // (the backup stop: its own test)
  auto a = started(Policy::kMmh);
  KinematicState before;
  const double t1 = flyToCruise(*a, &before);
  const Vector3d p1 = before.position;
  const Vector3d pillar(p1.x() + 7.0, 0.0, 0.0);
  putPillar(pillar.x(), 0.0, 0.4);
  a->onMapUpdated(grid_, ++map_seq_, at(t1), at(t1));
  ASSERT_EQ(a->takeRequests().size(), 1u);  // EAM, which never answers; nor does SOM after it
  std::optional<CommitOut> stop;
  double stop_time = 0.0;
  for (double t = t1 + 0.01; t < t1 + 6.0 && !stop; t += 0.01) {
    const int64_t now = at(t);
    a->onOdometry(a->committed().state((now - a->committedStartUtime()) * 1e-6), now);
    a->takeRequests();
    stop = a->takeCommit();
    stop_time = t;
  }
  ASSERT_TRUE(stop.has_value());
  EXPECT_EQ(stop->mode, Mode::kStop);
  // Not at the first deadline, but once the danger came close; and the stop ends clear of it.
  EXPECT_GT(stop_time, t1 + 2.0 * params_.answer_deadline_s + 0.1);
  const Trajectory& t = stop->trajectory;
  EXPECT_FALSE(mmh::firstCollisionTime(grid_, t, 0.0, t.duration()).has_value());
  EXPECT_LT(t.velocity(t.duration()).norm(), 1e-6);
  EXPECT_LT((t.position(t.duration()) - pillar).head<2>().norm(), 0.4 + 1.5);  // it came close
}

// Every mode failed, the danger is far: while the stop waits, the committed trajectory bleeds
// speed along its own path, so that the next rounds start slower; the danger is answered.
TEST_F(ArbiterRules, AFailedRoundWithAFarDangerSlowsTheCommittedPathWhileTheStopWaits) {
  params_.stale_map_s = 10.0;
  params_.defer_far_collisions = false;
  params_.backup_stop = false;  // the slowdown alone (the backup stop: its own test)
  for (const double ratio : {1.0, 0.7}) {
    SCOPED_TRACE("ratio " + std::to_string(ratio));
    params_.failed_round_speed_ratio = ratio;
    clearGrid();
    auto a = started(Policy::kMmh);
    Trajectory path;
    int64_t path_start = 0;
    const double t1 = failARoundBeforeAFarPillar(*a, &path, &path_start);
    auto commit = a->takeCommit();
    const auto decisions = a->takeDecisions();
    ASSERT_FALSE(decisions.empty());
    EXPECT_EQ(decisions.front().outcome, Outcome::kFailed);
    if (ratio == 1.0) {
      EXPECT_FALSE(commit.has_value());  // off: the committed trajectory flies on
      continue;
    }
    ASSERT_TRUE(commit.has_value());
    EXPECT_NE(commit->mode, Mode::kStop);
    EXPECT_EQ(a->counters().failed_round_slowdowns, 1);
    ASSERT_EQ(decisions.size(), 2u);
    EXPECT_EQ(decisions.back().outcome, Outcome::kCommitted);
    EXPECT_NE(decisions.back().detail.find("slowing down"), std::string::npos);
    EXPECT_GT(decisions.back().threat_seen_utime, 0);  // the danger's first answer
    const Trajectory& slow = commit->trajectory;
    const double s0 = (commit->start_utime - path_start) * 1e-6;
    const double speed = path.velocity(s0).norm();
    EXPECT_NEAR(slow.velocity(0.0).norm(), speed, 1e-3);
    EXPECT_LE(slow.maxAcceleration(), params_.max_acc_mps2 * 1.001);
    // Down to the ratio once the transition is over (within the slowdown's fit), on the old path.
    EXPECT_LT(slow.velocity(0.5 * slow.duration()).norm(), ratio * speed * 1.05);
    EXPECT_LT(farthestFromPath(slow, path, s0), 0.02);
    // Every later round fails too (no mode answers): the stop still comes, slower and clear.
    std::optional<CommitOut> stop;
    for (double t = t1 + 0.02; t < t1 + 8.0 && !(stop && stop->mode == Mode::kStop); t += 0.01) {
      const int64_t now = at(t);
      a->onOdometry(a->committed().state((now - a->committedStartUtime()) * 1e-6), now);
      a->takeRequests();
      stop = a->takeCommit();
    }
    ASSERT_TRUE(stop.has_value());
    ASSERT_EQ(stop->mode, Mode::kStop);
    EXPECT_GT(a->counters().failed_round_slowdowns, 1);
    EXPECT_LT(stop->trajectory.velocity(0.0).norm(), ratio * speed * 1.05);
    const Trajectory& st = stop->trajectory;
    EXPECT_FALSE(mmh::firstCollisionTime(grid_, st, 0.0, st.duration()).has_value());
    EXPECT_LT(st.velocity(st.duration()).norm(), 1e-6);
  }
}

// Every mode failed, the danger is far: the vehicle flies on along the committed path (slowed or
// not), but what is committed ends in a stop clear of the danger, the backup stop, so the danger
// is answered at once. When no mode ever answers, the vehicle brakes on it, with no new commit,
// and a decision says so.
TEST_F(ArbiterRules, AFailedRoundWithAFarDangerCommitsThePathUpToABackupStopClearOfIt) {
  params_.stale_map_s = 10.0;
  params_.defer_far_collisions = false;
  // Also with the vehicle just above the fence's ceiling (setCeilingJustBelowTheVehicle): the
  // backup stop keeps to the tolerance band.
  struct Case {
    double ratio;
    bool above_fence;
  };
  for (const Case each : {Case{1.0, false}, Case{0.7, false}, Case{1.0, true}}) {
    const double ratio = each.ratio;
    SCOPED_TRACE("ratio " + std::to_string(ratio) + (each.above_fence ? ", above the fence" : ""));
    params_.failed_round_speed_ratio = ratio;
    setCeilingJustBelowTheVehicle(each.above_fence);
    clearGrid();
    auto a = started(Policy::kMmh);
    Trajectory path;
    int64_t path_start = 0;
    const double t1 = failARoundBeforeAFarPillar(*a, &path, &path_start);
    if (each.above_fence) {
      ASSERT_GT(path.position((at(t1) - path_start) * 1e-6).z(), params_.geofence_max_m.z());
    }
    ASSERT_TRUE(
        mmh::firstCollisionTime(grid_, path, (at(t1) - path_start) * 1e-6, path.duration()));
    auto commit = a->takeCommit();
    ASSERT_TRUE(commit.has_value());
    EXPECT_NE(commit->mode, Mode::kStop);
    EXPECT_EQ(a->counters().backup_stops, 1);
    EXPECT_EQ(a->counters().failed_round_slowdowns, ratio < 1.0 ? 1 : 0);
    EXPECT_EQ(a->counters().stops, 0);
    const auto decisions = a->takeDecisions();
    ASSERT_EQ(decisions.size(), 2u);
    EXPECT_EQ(decisions.back().outcome, Outcome::kCommitted);
    EXPECT_NE(decisions.back().detail.find("backup stop"), std::string::npos);
    EXPECT_GT(decisions.back().threat_seen_utime, 0);  // the danger's answer, on its own map
    // Checked here, not by the arbiter's code: clear of the pillar, at rest, within the limits,
    // and on the committed path at first.
    const Trajectory& backup = commit->trajectory;
    EXPECT_FALSE(mmh::firstCollisionTime(grid_, backup, 0.0, backup.duration()).has_value());
    EXPECT_LT(backup.velocity(backup.duration()).norm(), 1e-6);
    EXPECT_LE(backup.maxAcceleration(), params_.max_acc_mps2 * 1.001);
    const double s0 = (commit->start_utime - path_start) * 1e-6;
    EXPECT_LT((backup.state(0.0).velocity - path.velocity(s0)).norm(), 1e-6);
    EXPECT_LT(farthestFromPath(backup, path, s0), 0.02);  // braking along it, not swerving
    for (double s = 0.0; s <= backup.duration(); s += 0.01) {
      EXPECT_LE(backup.position(s).z(),
                params_.geofence_max_m.z() + params_.geofence_tolerance_m + 1e-9);
    }
    // No mode answers again: each failed round moves the backup stop on as far as it stays
    // clear, every trajectory the vehicle is sent starts where it is and ends at rest clear of
    // the pillar; then it brakes on the last one, without a new commit, and a decision says so.
    bool braking = false;
    for (double t = t1 + 0.02; t < t1 + 8.0 && !braking; t += 0.01) {
      const int64_t now = at(t);
      const KinematicState flying = a->committed().state((now - a->committedStartUtime()) * 1e-6);
      const Trajectory before_round = a->committed();
      const int64_t before_start = a->committedStartUtime();
      a->onOdometry(flying, now);
      for (auto& r : a->takeRequests()) a->onAnswer(failedAnswer(r), now + 1000);
      if (auto c = a->takeCommit()) {
        EXPECT_NE(c->mode, Mode::kStop);
        const Trajectory& f = c->trajectory;
        EXPECT_FALSE(mmh::firstCollisionTime(grid_, f, 0.0, f.duration()).has_value());
        EXPECT_LT(f.velocity(f.duration()).norm(), 1e-6);
        const double from_s = (c->start_utime - before_start) * 1e-6;
        EXPECT_LT((f.position(0.0) - before_round.position(from_s)).norm(), 1e-6);
        EXPECT_LT((f.velocity(0.0) - before_round.velocity(from_s)).norm(), 1e-6);
      }
      for (const auto& d : a->takeDecisions()) {
        braking |=
            d.outcome == Outcome::kStopping && d.detail.find("backup stop") != std::string::npos;
      }
    }
    EXPECT_TRUE(braking);
    EXPECT_EQ(a->counters().stops, 1);
  }
}

// With a backup stop committed, the maps that show the danger again beyond it show nothing new:
// no decision is reported as a danger's answer. An obstacle that a later map shows on the backup
// stop itself is a new danger: the stop that answers it says when that map showed it.
TEST_F(ArbiterRules, OnlyAnObstacleMappedOnTheBackupStopIsANewDanger) {
  params_.stale_map_s = 10.0;
  params_.defer_far_collisions = false;
  params_.failed_round_speed_ratio = 1.0;
  auto a = started(Policy::kMmh);
  Trajectory path;
  int64_t path_start = 0;
  const double t1 = failARoundBeforeAFarPillar(*a, &path, &path_start);
  auto commit = a->takeCommit();
  ASSERT_TRUE(commit.has_value());
  ASSERT_EQ(a->counters().backup_stops, 1);
  a->takeDecisions();
  // The same map again: a round for the pillar beyond the backup stop, which fails.
  const double t_again = t1 + 0.05;
  a->onMapUpdated(grid_, ++map_seq_, at(t_again), at(t_again));
  a->onOdometry(a->committed().state((at(t_again) - a->committedStartUtime()) * 1e-6), at(t_again));
  const auto again = a->takeRequests();
  ASSERT_FALSE(again.empty());
  for (const auto& r : again) a->onAnswer(failedAnswer(r), at(t_again) + 1000);
  commit = a->takeCommit();
  for (const auto& d : a->takeDecisions()) EXPECT_EQ(d.threat_seen_utime, 0) << d.detail;
  // A second pillar 1.5 m ahead, on the way to the backup stop.
  const double t2 = t1 + 0.1;
  const KinematicState here = a->committed().state((at(t2) - a->committedStartUtime()) * 1e-6);
  putPillar(here.position.x() + 1.5, here.position.y(), 0.3);
  ASSERT_TRUE(
      mmh::firstCollisionTime(grid_, commit->trajectory, 0.0, commit->trajectory.duration()));
  a->onMapUpdated(grid_, ++map_seq_, at(t2), at(t2));
  a->onOdometry(here, at(t2));
  int64_t answered_seen = 0;
  for (double t = t2; t < t2 + 1.0 && answered_seen == 0; t += 0.01) {
    const int64_t now = at(t);
    a->onOdometry(a->committed().state((now - a->committedStartUtime()) * 1e-6), now);
    for (auto& r : a->takeRequests()) a->onAnswer(failedAnswer(r), now + 1000);
    a->takeCommit();
    for (const auto& d : a->takeDecisions()) {
      if (d.outcome != Outcome::kFailed && d.threat_seen_utime != 0)
        answered_seen = d.threat_seen_utime;
    }
  }
  EXPECT_EQ(answered_seen, at(t2));
}

// A backup stop brakes along the committed path. Where that path passes a mapped obstacle whose
// side toward it the sensor has not seen, the stop must end before that side, though the centre
// line stays in mapped space: the side may reach into the airframe's way.
TEST_F(ArbiterRules, ABackupStopEndsBeforeAnObstaclesUnseenSideBesideThePath) {
  params_.stale_map_s = 10.0;
  params_.defer_far_collisions = false;
  params_.failed_round_speed_ratio = 1.0;
  for (const double hidden_face_m : {0.3, 0.0}) {
    SCOPED_TRACE("hidden_face_m " + std::to_string(hidden_face_m));
    params_.hidden_face_m = hidden_face_m;
    clearGrid();
    auto a = started(Policy::kMmh);
    KinematicState before;
    const double t1 = flyToCruise(*a, &before);
    // 4 m ahead, a trunk 0.45-0.75 m beside the path (at y = 0), seen from above only: the cells
    // between it and the path (y 0.1-0.4 m) unknown. Its unseen side lies beyond the committed
    // path's reach, so only the pillar 7 m ahead is a danger.
    const double face_x = before.position.x() + 4.0;
    for (int64_t i = 0; i < grid_.numCells(); ++i) {
      const Vector3d c = grid_.centerOfLocal(grid_.localFromLinear(i));
      if (c.x() < face_x || c.x() > face_x + 0.6) continue;
      if (c.y() > 0.1 && c.y() < 0.4) grid_.setLinear(i, mmh::Occupancy::kUnknown);
      if (c.y() > 0.4 && c.y() < 0.8) grid_.setLinear(i, mmh::Occupancy::kOccupied);
    }
    putPillar(before.position.x() + 7.0, 0.0, 0.4);
    a->onMapUpdated(grid_, ++map_seq_, at(t1), at(t1));
    auto eam = a->takeRequests();
    ASSERT_EQ(eam.size(), 1u);
    a->onAnswer(failedAnswer(eam[0]), at(t1 + 0.005));
    auto commit = a->takeCommit();
    ASSERT_TRUE(commit.has_value());
    ASSERT_EQ(a->counters().backup_stops, 1);
    const Trajectory& backup = commit->trajectory;
    EXPECT_FALSE(mmh::firstCollisionTime(grid_, backup, 0.0, backup.duration()).has_value());
    const double rest_x = backup.position(backup.duration()).x();
    if (hidden_face_m > 0.0) {
      // Checked here by the airframe's reach, not by the arbiter's rule: braking straight along
      // y = 0, at rest before the airframe reaches the unknown cells.
      EXPECT_LT(rest_x + params_.vehicle_radius_m, face_x);
    } else {
      // The centre line alone: braking goes on past the trunk, up to the pillar.
      EXPECT_GT(rest_x, face_x + 0.6);
    }
  }
}

TEST_F(ArbiterRules, WhileStuckAFailedRoundWithTheDangerCloseStopsAtOnce) {
  // Stuck from the start: retries come at most every stuck_retry_period_s, too late for a danger
  // this close.
  double t1 = 0.0;
  auto a = stuckBeforeAPillar(&t1);
  a->onMapUpdated(grid_, ++map_seq_, at(t1), at(t1));
  auto eam = a->takeRequests();
  ASSERT_EQ(eam.size(), 1u);
  a->takeDecisions();
  a->onAnswer(failedAnswer(eam[0]), at(t1 + 0.005));
  // SOM is left in the chain but held back for a second: the stop comes now.
  auto commit = a->takeCommit();
  ASSERT_TRUE(commit.has_value());
  EXPECT_EQ(commit->mode, Mode::kStop);
  const Trajectory& t = commit->trajectory;
  EXPECT_FALSE(mmh::firstCollisionTime(grid_, t, 0.0, t.duration()).has_value());
}

TEST_F(ArbiterRules, AStuckVehicleBacksOffAskingEveryModeOfTheChainAtOnce) {
  double t1 = 0.0;
  auto a = stuckBeforeAPillar(&t1);
  // Every mode fails from here on: the vehicle stops, then retries until a back-off round.
  std::vector<PlanRequestOut> back_off;
  for (double t = t1; t < t1 + 10.0 && back_off.empty(); t += 0.01) {
    const int64_t now = at(t);
    if (std::lround(t * 100) % 10 == 0) a->onMapUpdated(grid_, ++map_seq_, now, now);
    a->onOdometry(a->committed().state((now - a->committedStartUtime()) * 1e-6), now);
    const std::vector<PlanRequestOut> round = a->takeRequests();
    if (a->counters().back_offs > 0) back_off = round;
    for (const auto& r : round) a->onAnswer(failedAnswer(r), now + 1000);
    a->takeCommit();
  }
  ASSERT_EQ(back_off.size(), 2u) << "no back-off round asking two modes";
  std::vector<Mode> asked = {back_off[0].mode, back_off[1].mode};
  std::sort(asked.begin(), asked.end());
  std::vector<Mode> chain = {Mode::kSom, Mode::kEam};
  std::sort(chain.begin(), chain.end());
  EXPECT_EQ(asked, chain);
  for (const auto& r : back_off) {
    EXPECT_EQ(r.trigger, Trigger::kRetry);
    // Back along the way it came (toward the start), at least backoff_min_distance_m away, with
    // no reference to repair: a fresh plan from where it stands.
    EXPECT_LT(r.target.x(), r.start.position.x());
    EXPECT_GE((r.target - r.start.position).norm(), params_.backoff_min_distance_m - 1e-9);
    EXPECT_TRUE(r.reference.empty());
  }
}

// When no mode answers the back-off either (a gap the mapped outlines have closed behind the
// vehicle), it flies back the way it came, slowly, to the back-off point, and only then do the
// modes plan again.
TEST_F(ArbiterRules, ABackOffNoModeAnswersIsFlownBackTheWayTheVehicleCame) {
  // Also with the vehicle just above the fence's ceiling (setCeilingJustBelowTheVehicle): the way
  // back keeps to the tolerance band.
  for (const bool above_fence : {false, true}) {
    SCOPED_TRACE(above_fence ? "above the fence" : "inside the fence");
    clearGrid();
    setCeilingJustBelowTheVehicle(above_fence);
    double t1 = 0.0;
    auto a = stuckBeforeAPillar(&t1);
    std::vector<Vector3d> flown;
    std::optional<CommitOut> retrace;
    Vector3d back_off_target = Vector3d::Zero();
    double t = t1;
    for (; t < t1 + 10.0 && !retrace; t += 0.01) {
      const int64_t now = at(t);
      if (std::lround(t * 100) % 10 == 0) a->onMapUpdated(grid_, ++map_seq_, now, now);
      const KinematicState s = a->committed().state((now - a->committedStartUtime()) * 1e-6);
      flown.push_back(s.position);
      a->onOdometry(s, now);
      const std::vector<PlanRequestOut> round = a->takeRequests();
      if (a->counters().back_offs > 0 && !round.empty()) back_off_target = round[0].target;
      for (const auto& r : round) a->onAnswer(failedAnswer(r), now + 1000);
      if (auto c = a->takeCommit(); c && c->mode == Mode::kNone) retrace = c;
    }
    ASSERT_TRUE(retrace.has_value()) << "no retrace";
    if (above_fence) {
      EXPECT_GT(retrace->trajectory.position(0.0).z(), params_.geofence_max_m.z());
    }
    EXPECT_EQ(a->counters().retraces, 1);
    EXPECT_GE(a->counters().back_offs, 1);
    // From rest (a vehicle still braking would first run on towards what it is stuck at).
    EXPECT_LE(retrace->trajectory.velocity(0.0).norm(), params_.braking_speed_mps);
    bool said = false;
    for (const auto& d : a->takeDecisions())
      said |= d.detail.find("flying back") != std::string::npos;
    EXPECT_TRUE(said);
    // Checked here: from where the vehicle is to the back-off point, at rest there, within the
    // limits, along positions it flew (every sample near one), clear of the pillar.
    const Trajectory& way = retrace->trajectory;
    EXPECT_LT((way.position(way.duration()) - back_off_target).norm(), 1e-9);
    EXPECT_LT(way.velocity(way.duration()).norm(), 1e-9);
    EXPECT_LE(way.maxSpeed(), params_.max_vel_mps);
    EXPECT_LE(way.maxAcceleration(), params_.max_acc_mps2);
    EXPECT_LT(way.position(way.duration()).x(), way.position(0.0).x() - 1.0);  // back, away
    for (double u = 0.0; u <= way.duration(); u += 0.05) {
      double nearest = 1e9;
      for (const Vector3d& p : flown) nearest = std::min(nearest, (p - way.position(u)).norm());
      EXPECT_LT(nearest, 0.1) << "at " << u << " s of the way back";
      EXPECT_GT(mmh::occupiedDistance(grid_, way.position(u), 1.0), 0.4);
      EXPECT_LE(way.position(u).z(), params_.geofence_max_m.z() + params_.geofence_tolerance_m);
    }
    // Flown to its end with no request (no halfway replan from inside the spot), then the modes
    // are asked again from the back-off point.
    const double end_s = t + way.duration();
    std::vector<PlanRequestOut> next;
    for (; t < end_s + 1.0 && next.empty(); t += 0.01) {
      const int64_t now = at(t);
      if (std::lround(t * 100) % 10 == 0) a->onMapUpdated(grid_, ++map_seq_, now, now);
      a->onOdometry(a->committed().state((now - a->committedStartUtime()) * 1e-6), now);
      next = a->takeRequests();
    }
    ASSERT_FALSE(next.empty());
    EXPECT_GT(t, end_s - 0.05);
    EXPECT_LT((next[0].start.position - back_off_target).norm(), 0.05);
  }
}

TEST_F(ArbiterRules, UnmappedSpaceWithinStoppingReachAsksARoundThenStopsBeforeIt) {
  auto a = started(Policy::kMmh);
  KinematicState before;
  const double t1 = flyToCruise(*a, &before);
  // A slab the sensor never saw, across the way, 2.2 m ahead: within the reach of a vehicle
  // this fast (lead and decision margin, then its stopping distance), though nothing is in it.
  const double slab_x = before.position.x() + 2.2;
  for (int64_t i = 0; i < grid_.numCells(); ++i) {
    const double x = grid_.centerOfLocal(grid_.localFromLinear(i)).x();
    if (x >= slab_x && x < slab_x + 0.5) grid_.setLinear(i, mmh::Occupancy::kUnknown);
  }
  a->onMapUpdated(grid_, ++map_seq_, at(t1), at(t1));
  auto requests = a->takeRequests();
  ASSERT_EQ(requests.size(), 1u);
  EXPECT_EQ(requests[0].trigger, Trigger::kCollision);
  // No mode answers: the fallback chain runs out and the vehicle stops short of the slab.
  std::optional<CommitOut> stop;
  std::string details;
  for (double t = t1 + 0.01; t < t1 + 6.0 && !stop; t += 0.01) {
    const int64_t now = at(t);
    if (std::lround(t * 100) % 10 == 0) a->onMapUpdated(grid_, ++map_seq_, now, now);
    a->onOdometry(a->committed().state((now - a->committedStartUtime()) * 1e-6), now);
    a->takeRequests();
    for (const auto& d : a->takeDecisions()) details += d.detail + "\n";
    stop = a->takeCommit();
  }
  ASSERT_TRUE(stop.has_value());
  EXPECT_EQ(stop->mode, Mode::kStop);
  EXPECT_NE(details.find("unmapped space"), std::string::npos) << details;
  const Trajectory& t = stop->trajectory;
  EXPECT_LT(t.velocity(t.duration()).norm(), 1e-6);
  EXPECT_LT(t.position(t.duration()).x(), slab_x);
  EXPECT_EQ(mmh::assessStop(grid_, t, 1.0).unknown_m, 0.0);
}

TEST_F(ArbiterRules, WithoutProgressRetriesSlowDownThenTheGoalIsUnreachableUntilANewOne) {
  auto a = started(Policy::kMmh, false);
  int requests = 0;
  std::optional<DecisionOut> unreachable;
  // Every mode fails; the vehicle stays at rest with fresh maps at 10 Hz for 40 s.
  for (double t = 0.0; t < 40.0; t += 0.01) {
    const int64_t now = at(t);
    if (std::lround(t * 100) % 10 == 0) a->onMapUpdated(grid_, ++map_seq_, now, now);
    a->onOdometry(rest(Vector3d(0, 0, 1.2)), now);
    for (const auto& r : a->takeRequests()) {
      ++requests;
      a->onAnswer(failedAnswer(r), now);
    }
    for (const auto& d : a->takeDecisions()) {
      if (d.outcome == Outcome::kUnreachable) unreachable = d;
    }
  }
  ASSERT_TRUE(unreachable.has_value());
  EXPECT_EQ(a->phase(), Phase::kUnreachable);
  EXPECT_NE(unreachable->detail.find("unreachable: no progress"), std::string::npos)
      << unreachable->detail;
  EXPECT_NE(unreachable->detail.find("no path"), std::string::npos);  // the last failure
  EXPECT_EQ(a->counters().unreachable_goals, 1);
  // Without the stuck detector: SOM and EAM on every map, 800 calls in 40 s. With it: so for
  // stuck_still_s (at rest, no answer committed; stuck_after_s for a vehicle that moves), then
  // one call per stuck_retry_period_s, then one per unreachable_retry_s.
  ASSERT_LT(params_.stuck_still_s, params_.stuck_after_s);
  const double expected =
      params_.stuck_still_s * 10.0 * 2.0 +
      (params_.give_up_s - params_.stuck_still_s) / params_.stuck_retry_period_s +
      (40.0 - params_.give_up_s) / params_.unreachable_retry_s;
  EXPECT_LE(requests, expected + 4);
  // A new goal is planned for at once.
  std::string why;
  ASSERT_TRUE(a->setGoal(2, Vector3d(10, 5, 1.2), at(40.0), &why)) << why;
  a->setAwareness(false, 1, 2, map_seq_);
  a->onOdometry(rest(Vector3d(0, 0, 1.2)), at(40.01));
  EXPECT_EQ(a->takeRequests().size(), 1u);
  EXPECT_EQ(a->phase(), Phase::kTracking);
}

TEST_F(ArbiterRules, AGoalGivenUpHoldsAVehicleWhosePlanHasNotYetMovedIt) {
  auto a = started(Policy::kMmh, false);
  // An answer that leaves rest slowly, x = 0.01 t^3 for 3 s: under stop_min_speed_mps for its
  // first 1.2 s, 0.27 m/s at its end.
  auto slowStart = [](const PlanRequestOut& r) {
    ModeAnswer ans = okAnswer(r);
    mmh::Piece p;
    p.duration = 3.0;
    p.coeffs.col(0) = r.start.position;
    p.coeffs.col(3) = Vector3d(0.01, 0.0, 0.0);
    ans.trajectory = mmh::Trajectory({p});
    return ans;
  };
  // Every mode fails, the vehicle at rest, until the retry in the last second before the goal
  // is given up: that answer is committed, and the goal is given up before it has moved the
  // vehicle.
  std::optional<CommitOut> last_plan;
  std::optional<CommitOut> after_give_up;
  std::optional<double> committed_at_s;
  bool gave_up = false;
  const double answer_from_s = params_.give_up_s - params_.stuck_retry_period_s;
  for (double t = 0.0; t < params_.give_up_s + 2.0 && !after_give_up; t += 0.01) {
    const int64_t now = at(t);
    if (std::lround(t * 100) % 10 == 0) a->onMapUpdated(grid_, ++map_seq_, now, now);
    a->onOdometry(rest(Vector3d(0, 0, 1.2)), now);
    for (const auto& r : a->takeRequests())
      a->onAnswer(t >= answer_from_s && !gave_up ? slowStart(r) : failedAnswer(r), now);
    for (const auto& d : a->takeDecisions()) gave_up |= d.outcome == Outcome::kUnreachable;
    if (auto c = a->takeCommit()) {
      if (gave_up) {
        after_give_up = c;
      } else {
        last_plan = c;
        committed_at_s = t;
      }
    }
  }
  ASSERT_TRUE(gave_up);
  ASSERT_TRUE(last_plan.has_value());
  ASSERT_NE(last_plan->mode, Mode::kStop);
  ASSERT_TRUE(committed_at_s.has_value());
  // Holding: the plan that would fly off, unchecked while the goal is given up, is replaced by a
  // stop where the vehicle is.
  ASSERT_TRUE(after_give_up.has_value()) << "the plan committed at " << *committed_at_s
                                         << " s was left to fly after the goal was given up";
  EXPECT_EQ(after_give_up->mode, Mode::kStop);
  const mmh::Trajectory& hold = after_give_up->trajectory;
  EXPECT_LT((hold.position(hold.duration()) - Vector3d(0, 0, 1.2)).norm(), 0.05);
  EXPECT_LT(hold.maxSpeed(), params_.stop_min_speed_mps);
}

TEST_F(ArbiterRules, AnUnreachableGoalResumesWhenANewMapOpensAWay) {
  auto a = started(Policy::kMmh, false);
  // Every mode fails until the vehicle, holding at rest, is declared unreachable.
  double t = 0.0;
  for (; a->phase() != Phase::kUnreachable && t < 60.0; t += 0.01) {
    const int64_t now = at(t);
    if (std::lround(t * 100) % 10 == 0) a->onMapUpdated(grid_, ++map_seq_, now, now);
    a->onOdometry(rest(Vector3d(0, 0, 1.2)), now);
    for (const auto& r : a->takeRequests()) a->onAnswer(failedAnswer(r), now);
  }
  ASSERT_EQ(a->phase(), Phase::kUnreachable);
  a->takeDecisions();
  // Newer maps open a way: the modes answer again. The next periodic retry commits, and the
  // arbiter tracks the same goal again.
  std::optional<CommitOut> resumed;
  const double until = t + params_.unreachable_retry_s + 1.0;
  for (; t < until && !resumed; t += 0.01) {
    const int64_t now = at(t);
    if (std::lround(t * 100) % 10 == 0) a->onMapUpdated(grid_, ++map_seq_, now, now);
    a->onOdometry(rest(Vector3d(0, 0, 1.2)), now);
    for (const auto& r : a->takeRequests()) a->onAnswer(okAnswer(r), now);
    resumed = a->takeCommit();
  }
  ASSERT_TRUE(resumed.has_value()) << "no retry within unreachable_retry_s of the way opening";
  EXPECT_NE(resumed->mode, Mode::kStop);
  EXPECT_EQ(a->phase(), Phase::kTracking);
  EXPECT_EQ(a->counters().unreachable_goals, 1);
}

TEST_F(ArbiterRules, NewGoalTriggersAReplan) {
  auto a = started(Policy::kMmh);
  a->onAnswer(okAnswer(a->takeRequests().at(0)), at(0.001));
  ASSERT_TRUE(a->takeCommit());
  fly(*a, 0.01, 1.0);
  std::string why;
  a->setAwareness(true, 0, 2, map_seq_);
  ASSERT_TRUE(a->setGoal(2, Vector3d(0, 20, 1.2), at(1.0), &why));
  auto requests = a->takeRequests();
  ASSERT_EQ(requests.size(), 1u);
  EXPECT_EQ(requests[0].trigger, Trigger::kGoalChanged);
  EXPECT_NEAR(requests[0].goal.y(), 20.0, 1e-12);
}

TEST_F(ArbiterRules, GoalsOutsideTheFenceOrDeepInsideObstaclesAreRefused) {
  putPillar(5.0, 5.0, 2.0);  // the nearest free point is farther than goal_relocate_radius_m
  params_.policy = Policy::kMmh;
  Arbiter a(params_);
  a.onMapUpdated(grid_, 1, at(0), at(0));
  std::string why;
  EXPECT_FALSE(a.setGoal(1, Vector3d(100, 0, 1.2), at(0), &why));
  EXPECT_NE(why.find("outside the geofence (x = 100 > 30)"), std::string::npos) << why;
  EXPECT_NE(why.find("geofence.max_m"), std::string::npos) << why;
  EXPECT_FALSE(a.setGoal(2, Vector3d(5.0, 5.0, 1.2), at(0), &why));
  EXPECT_NE(why.find("obstacle"), std::string::npos);
  EXPECT_NE(why.find("arbiter.goal_relocate_radius_m"), std::string::npos) << why;
  EXPECT_FALSE(a.setGoal(3, Vector3d(NAN, 0, 1), at(0), &why));
  EXPECT_EQ(a.counters().rejected_goals, 3);
  EXPECT_FALSE(a.hasGoal());
  auto decisions = a.takeDecisions();
  ASSERT_EQ(decisions.size(), 3u);
  EXPECT_EQ(decisions[0].outcome, Outcome::kRejected);
}

TEST_F(ArbiterRules, DiscontinuousAnswersAreRejected) {
  auto a = started(Policy::kMmh);
  auto r = a->takeRequests().at(0);
  ModeAnswer bad = okAnswer(r);
  KinematicState shifted = r.start;
  shifted.position.x() += 0.5;
  bad.trajectory = simplePlan(shifted, r.target);
  a->onAnswer(bad, at(0.001));
  EXPECT_FALSE(a->takeCommit().has_value());
  EXPECT_EQ(a->counters().rejected_answers, 1);
}

TEST_F(ArbiterRules, StaleMapStopsTheVehicle) {
  auto a = started(Policy::kMmh);
  a->onAnswer(okAnswer(a->takeRequests().at(0)), at(0.001));
  ASSERT_TRUE(a->takeCommit());
  // No map for longer than stale_map_s while flying.
  fly(*a, 0.01, params_.stale_map_s + 0.2, false);
  auto commit = a->takeCommit();
  ASSERT_TRUE(commit.has_value());
  EXPECT_EQ(commit->mode, Mode::kStop);
}

TEST_F(ArbiterRules, EgoPolicyReplansEveryFixedDistanceWithEam) {
  auto a = started(Policy::kEgo);
  auto r = a->takeRequests().at(0);
  EXPECT_EQ(r.mode, Mode::kEam);
  a->onAnswer(okAnswer(r), at(0.001));
  ASSERT_TRUE(a->takeCommit());
  std::vector<PlanRequestOut> next;
  double t = 0.01;
  KinematicState s;
  for (; t < 20 && next.empty(); t += 0.01) {
    s = a->committed().state((at(t) - a->committedStartUtime()) * 1e-6);
    // Keep the map fresh.
    if (std::lround(t * 100) % 10 == 0) a->onMapUpdated(grid_, ++map_seq_, at(t), at(t));
    a->onOdometry(s, at(t));
    next = a->takeRequests();
  }
  ASSERT_EQ(next.size(), 1u);
  EXPECT_EQ(next[0].trigger, Trigger::kFixed);
  EXPECT_EQ(next[0].mode, Mode::kEam);
  EXPECT_NEAR((s.position - Vector3d(0, 0, 1.2)).norm(), params_.fixed_replan_distance_m, 0.05);
}

TEST_F(ArbiterRules, AnswersLeavingTheGeofenceAreRejected) {
  auto a = started(Policy::kMmh);
  auto r = a->takeRequests().at(0);
  ModeAnswer bad = okAnswer(r);
  bad.trajectory = simplePlan(r.start, Vector3d(3, 0, 3.0));  // the fence ends at z = 2.7 m
  a->onAnswer(bad, at(0.001));
  EXPECT_FALSE(a->takeCommit().has_value());
  EXPECT_EQ(a->counters().rejected_answers, 1);
}

TEST_F(ArbiterRules, OverlongAnswersAreRejectedBeforeBeingWalked) {
  auto a = started(Policy::kMmh);
  auto r = a->takeRequests().at(0);
  ModeAnswer bad = okAnswer(r);
  // A valid message can hold 4096 pieces of 1e4 s: hovering at the end for 4e7 s.
  mmh::Piece hover;
  hover.duration = 1e4;
  hover.coeffs.col(0) = bad.trajectory.position(bad.trajectory.duration());
  for (int i = 0; i < 4000; ++i) bad.trajectory.append(hover);
  a->onAnswer(bad, at(0.001));
  EXPECT_FALSE(a->takeCommit().has_value());
  EXPECT_EQ(a->counters().rejected_answers, 1);
}

TEST_F(ArbiterRules, StoppedOdometryStopsPlanningUntilItReturns) {
  auto a = started(Policy::kMmh);
  a->onAnswer(okAnswer(a->takeRequests().at(0)), at(0.001));
  ASSERT_TRUE(a->takeCommit());
  ASSERT_TRUE(fly(*a, 0.01, 1.0).empty());
  a->takeDecisions();
  // Maps keep coming, ODOMETRY does not.
  std::optional<CommitOut> stop;
  double t = 1.0;
  for (; t < 1.0 + params_.stale_odometry_s + 0.3; t += 0.1) {
    a->onMapUpdated(grid_, ++map_seq_, at(t), at(t));
    EXPECT_TRUE(a->takeRequests().empty()) << "planned at " << t << " s without fresh odometry";
    if (auto c = a->takeCommit()) {
      ASSERT_FALSE(stop.has_value()) << "a second commit while odometry is stale";
      stop = c;
    }
  }
  ASSERT_TRUE(stop.has_value());
  EXPECT_EQ(stop->mode, Mode::kStop);
  EXPECT_TRUE(a->odometryStale(at(t)));
  EXPECT_EQ(a->counters().stale_odometry, 1);
  auto decisions = a->takeDecisions();
  ASSERT_FALSE(decisions.empty());
  EXPECT_EQ(decisions.back().outcome, Outcome::kStopping);
  EXPECT_NE(decisions.back().detail.find("ODOMETRY is stale"), std::string::npos);
  // Odometry returns: planning resumes from the committed (stopping) trajectory.
  auto resumed = fly(*a, t, t + 0.5);
  ASSERT_FALSE(resumed.empty());
  EXPECT_FALSE(a->odometryStale(at(t + 0.5)));
  EXPECT_EQ(a->counters().stale_odometry, 1);
}

TEST_F(ArbiterRules, StoppedOdometryDetectedFromTheRepeatedGoal) {
  auto a = started(Policy::kMmh);
  a->onAnswer(okAnswer(a->takeRequests().at(0)), at(0.001));
  ASSERT_TRUE(a->takeCommit());
  ASSERT_TRUE(fly(*a, 0.01, 1.0).empty());
  // Everything stops but the goal publisher (1 Hz, its own clock).
  std::string why;
  EXPECT_TRUE(a->setGoal(1, goal_, at(2.0), &why));
  auto commit = a->takeCommit();
  ASSERT_TRUE(commit.has_value());
  EXPECT_EQ(commit->mode, Mode::kStop);
  EXPECT_EQ(a->counters().stale_odometry, 1);
}

TEST_F(ArbiterRules, StoppedOdometryDetectedByTheClockAlone) {
  auto a = started(Policy::kMmh);
  a->onAnswer(okAnswer(a->takeRequests().at(0)), at(0.001));
  ASSERT_TRUE(a->takeCommit());
  ASSERT_TRUE(fly(*a, 0.01, 1.0).empty());
  a->takeDecisions();
  // Every input falls silent; the real-time node's idle tick moves the clock on.
  a->onClock(at(1.0 + 0.5 * params_.stale_odometry_s));
  EXPECT_FALSE(a->takeCommit().has_value()) << "stopped before ODOMETRY was stale";
  a->onClock(at(1.0 + params_.stale_odometry_s + 0.05));
  auto stop = a->takeCommit();
  ASSERT_TRUE(stop.has_value());
  EXPECT_EQ(stop->mode, Mode::kStop);
  EXPECT_EQ(a->now(), at(1.0 + params_.stale_odometry_s + 0.05));
  EXPECT_EQ(a->counters().stale_odometry, 1);
  // Further ticks of the same silence commit nothing more.
  a->onClock(at(2.5));
  EXPECT_FALSE(a->takeCommit().has_value());
  EXPECT_TRUE(a->takeRequests().empty());
}

TEST_F(ArbiterRules, AnswerArrivingWhileOdometryIsStaleIsNotCommitted) {
  params_.replan_lead_s = 1.0;
  params_.answer_deadline_s = 1.0;
  auto a = started(Policy::kMmh);
  auto r = a->takeRequests().at(0);
  // No odometry since 0 s; a map at 0.6 s moves the clock past stale_odometry_s.
  a->onMapUpdated(grid_, ++map_seq_, at(0.6), at(0.6));
  a->onAnswer(okAnswer(r), at(0.7));
  EXPECT_FALSE(a->takeCommit().has_value());
  EXPECT_EQ(a->counters().not_committed_stale_odom, 1);
  auto decisions = a->takeDecisions();
  ASSERT_FALSE(decisions.empty());
  EXPECT_EQ(decisions.front().outcome, Outcome::kFailed);
  EXPECT_NE(decisions.front().detail.find("ODOMETRY is stale"), std::string::npos);
}

TEST_F(ArbiterRules, SilentModeFallsBackToTheNextMode) {
  auto a = started(Policy::kMmh, false);
  auto som = a->takeRequests().at(0);
  ASSERT_EQ(som.mode, Mode::kSom);
  // SOM's process is gone: no answer. Odometry moves the clock past the deadline.
  a->onOdometry(rest(Vector3d(0, 0, 1.2)), at(params_.answer_deadline_s + 0.01));
  EXPECT_FALSE(a->takeCommit().has_value());
  EXPECT_EQ(a->counters().unanswered, 1);
  a->onOdometry(rest(Vector3d(0, 0, 1.2)), at(params_.answer_deadline_s + 0.02));
  auto eam = a->takeRequests();
  ASSERT_EQ(eam.size(), 1u);
  EXPECT_EQ(eam[0].mode, Mode::kEam);
  EXPECT_EQ(eam[0].trigger, Trigger::kRetry);
  a->onAnswer(okAnswer(eam[0]), at(params_.answer_deadline_s + 0.021));
  auto commit = a->takeCommit();
  ASSERT_TRUE(commit.has_value());
  EXPECT_EQ(commit->mode, Mode::kEam);
}

TEST_F(ArbiterRules, AnAnswerLeavesTheMarginOutwardsOnly) {
  // Same start 0.15 m from the pillar, inside the check margin. An answer that first slides
  // nearer to the pillar (through no occupied voxel, out of the margin 0.35 m from the start)
  // is refused: accepted, re-plans from in the margin crept along the obstacle a little nearer
  // each time until the vehicle touched it.
  putPillar(0.0, 0.45, 0.3);
  auto a = started(Policy::kMmh);
  auto r = a->takeRequests().at(0);
  ASSERT_TRUE(mmh::isPointBlocked(grid_, r.start.position));
  const Vector3d deeper(0.15, 0.1, 1.2);  // 0.08 m from the pillar's surface
  ASSERT_FALSE(grid_.isOccupiedPoint(deeper));
  const Trajectory in = simplePlan(r.start, deeper);
  mmh::KinematicState at_deeper;
  at_deeper.position = deeper;
  const Trajectory out = simplePlan(at_deeper, Vector3d(0.6, -0.2, 1.2));
  std::vector<mmh::Piece> pieces = in.pieces();
  pieces.insert(pieces.end(), out.pieces().begin(), out.pieces().end());
  ModeAnswer sliding = okAnswer(r);
  sliding.trajectory = Trajectory(pieces);
  ASSERT_FALSE(mmh::firstCollisionTime(grid_, sliding.trajectory, 0.0,
                                       sliding.trajectory.duration(),
                                       mmh::CollisionLayer::kOccupied));
  a->onAnswer(sliding, at(0.001));
  EXPECT_FALSE(a->takeCommit().has_value());
  EXPECT_EQ(a->counters().rejected_answers, 1);
  const auto decisions = a->takeDecisions();
  ASSERT_FALSE(decisions.empty());
  EXPECT_NE(decisions.back().detail.find("deeper"), std::string::npos) << decisions.back().detail;
}

TEST_F(ArbiterRules, AnAnswerMayLeaveTheMarginItStartsIn) {
  // The vehicle stopped 0.15 m from a newly mapped pillar: inside the check margin. Answers that
  // leave the margin near the start are accepted (else it would be stuck there for good), ones
  // that stay in it or go into the obstacle are not.
  putPillar(0.0, 0.45, 0.3);
  auto a = started(Policy::kMmh);
  auto r = a->takeRequests().at(0);
  ASSERT_TRUE(mmh::isPointBlocked(grid_, r.start.position));
  ModeAnswer into = okAnswer(r);
  into.trajectory = simplePlan(r.start, Vector3d(0.0, 3.0, 1.2));  // through the pillar
  a->onAnswer(into, at(0.001));
  EXPECT_FALSE(a->takeCommit().has_value());
  EXPECT_EQ(a->counters().rejected_answers, 1);
  // Retry (SOM) with an answer that leaves along +x.
  a->onOdometry(rest(Vector3d(0, 0, 1.2)), at(0.01));
  auto retry = a->takeRequests();
  ASSERT_EQ(retry.size(), 1u);
  a->onAnswer(okAnswer(retry[0]), at(0.011));
  auto commit = a->takeCommit();
  ASSERT_TRUE(commit.has_value());
  EXPECT_EQ(commit->mode, retry[0].mode);
  // Flown with new maps of the same pillar, the accepted escape is no collision: asked to
  // repair it, the modes would find the start in the margin again, fail, and the vehicle would
  // stop there, round after round.
  a->takeDecisions();
  for (const auto& request : fly(*a, 0.02, 0.45 * commit->trajectory.duration()))
    EXPECT_NE(request.trigger, Trigger::kCollision);
  for (const auto& d : a->takeDecisions()) EXPECT_NE(d.outcome, Outcome::kStopping) << d.detail;
}

// Answers that take 120 ms on a loaded computer miss the 40 ms deadline once; the next rounds
// wait 180 ms (1.5 x their p99) and start 190 ms ahead, so the answers are committed; once the
// slow answers have left the latency window, the configured budget returns.
TEST_F(ArbiterRules, LateAnswersLengthenTheBudgetUntilTheLoadGoes) {
  auto a = started(Policy::kMmh);
  const PlanRequestOut first = a->takeRequests().at(0);
  EXPECT_EQ(first.deadline_utime - at(0), static_cast<int64_t>(params_.answer_deadline_s * 1e6));
  a->onAnswer(okAnswer(first), at(0.12));
  EXPECT_FALSE(a->takeCommit());  // after its start time
  EXPECT_TRUE(a->latencyBudget().degraded);
  EXPECT_EQ(a->counters().degraded_periods, 1);

  a->onMapUpdated(grid_, ++map_seq_, at(0.25), at(0.25));  // the retry
  const std::vector<PlanRequestOut> retry = a->takeRequests();
  ASSERT_EQ(retry.size(), 1u);
  EXPECT_EQ(retry[0].deadline_utime - at(0.25), 180'000);
  EXPECT_EQ(retry[0].start_utime - at(0.25), 190'000);
  a->onAnswer(okAnswer(retry[0]), at(0.37));
  ASSERT_TRUE(a->takeCommit());

  // 10 s later (latency_window_s) without slow answers: back to the configured budget.
  const int64_t later = at(0.37) + static_cast<int64_t>(params_.latency_window_s * 1e6) + 10'000;
  a->onOdometry(a->committed().state((later - a->committedStartUtime()) * 1e-6), later);
  a->onMapUpdated(grid_, ++map_seq_, later, later);
  EXPECT_FALSE(a->latencyBudget().degraded);
  EXPECT_EQ(a->latencyBudget().answer_deadline_s, params_.answer_deadline_s);
  EXPECT_EQ(a->latencyBudget().replan_lead_s, params_.replan_lead_s);
}

// A round answered late lengthens the replan lead, so its answer starts far ahead; when the late
// answer leaves the latency window before that start, the lead shrinks. A stop decided then must
// still take over where the sent trajectory begins, not before it (the vehicle would jump).
TEST_F(ArbiterRules, NothingTakesOverBeforeTheStartOfTheTrajectoryItFollows) {
  params_.latency_window_s = 0.15;
  params_.stale_map_s = 0.05;
  auto a = started(Policy::kMmh);
  a->onAnswer(okAnswer(a->takeRequests().at(0)), at(0.12));  // late: not committed
  EXPECT_FALSE(a->takeCommit());
  a->onMapUpdated(grid_, ++map_seq_, at(0.25), at(0.25));
  const std::vector<PlanRequestOut> retry = a->takeRequests();
  ASSERT_EQ(retry.size(), 1u);
  a->onAnswer(okAnswer(retry[0]), at(0.26));
  const std::optional<CommitOut> sent = a->takeCommit();
  ASSERT_TRUE(sent.has_value());
  ASSERT_EQ(sent->start_utime, at(0.44));  // the lengthened lead

  // The late answer has left the window: the configured lead returns before the sent start.
  a->onMapUpdated(grid_, ++map_seq_, at(0.30), at(0.30));
  ASSERT_EQ(a->latencyBudget().replan_lead_s, params_.replan_lead_s);
  a->onOdometry(rest(Vector3d(0, 0, 1.2)), at(0.36));  // the map is stale now
  const std::optional<CommitOut> stop = a->takeCommit();
  ASSERT_TRUE(stop.has_value());
  ASSERT_EQ(stop->mode, Mode::kStop);
  EXPECT_GE(stop->start_utime, sent->start_utime);
  const KinematicState there =
      sent->trajectory.state((stop->start_utime - sent->start_utime) * 1e-6);
  EXPECT_LT((stop->trajectory.state(0.0).position - there.position).norm(), 1e-9);
  EXPECT_LT((stop->trajectory.state(0.0).velocity - there.velocity).norm(), 1e-9);
}

TEST_F(ArbiterRules, AnswersLaterThanTheFullSpeedDeadlineSlowTheVehicleUntilTheLoadGoes) {
  auto a = started(Policy::kMmh);
  // A first plan that reaches nearly 3 m/s, flown to its fastest part.
  const PlanRequestOut first = a->takeRequests().at(0);
  ModeAnswer fast = okAnswer(first);
  fast.trajectory = mmh::test::planFrom(first.start, first.target,
                                        1.875 * (first.target - first.start.position).norm() / 2.9);
  ASSERT_LE(fast.trajectory.maxAcceleration(), params_.max_acc_mps2);
  a->onAnswer(fast, at(0.001));
  ASSERT_TRUE(a->takeCommit());
  const double t1 = std::floor(0.4 * a->committed().duration() * 10.0) / 10.0;
  ASSERT_TRUE(fly(*a, 0.01, t1).empty());
  const KinematicState cruise = a->committed().state((at(t1) - a->committedStartUtime()) * 1e-6);
  // A new goal: its round is answered 0.3 s late (a loaded computer).
  std::string why;
  ASSERT_TRUE(a->setGoal(2, Vector3d(28, 2, 1.2), at(t1), &why)) << why;
  a->setAwareness(true, 0, 2, map_seq_);
  a->onOdometry(cruise, at(t1));
  const std::vector<PlanRequestOut> round = a->takeRequests();
  ASSERT_EQ(round.size(), 1u);
  EXPECT_EQ(round[0].max_speed_mps, params_.max_vel_mps);
  a->onAnswer(okAnswer(round[0]), at(t1 + 0.3));
  EXPECT_FALSE(a->takeCommit());  // after its start time
  const double limit = a->latencyBudget().speed_limit_mps;
  EXPECT_LT(limit, params_.max_vel_mps);
  EXPECT_NE(a->latencyBudget().why.find("speed lowered to"), std::string::npos);

  // The committed trajectory, faster than that, is slowed down along its path.
  const Trajectory before = a->committed();
  std::optional<CommitOut> slowed;
  std::string details;
  double t = t1 + 0.3;
  for (; t < t1 + 1.0 && !slowed; t += 0.01) {
    const int64_t now = at(t);
    if (std::lround(t * 100) % 10 == 0) a->onMapUpdated(grid_, ++map_seq_, now, now);
    a->onOdometry(a->committed().state((now - a->committedStartUtime()) * 1e-6), now);
    for (const auto& d : a->takeDecisions()) details += d.detail + "\n";
    a->takeRequests();
    slowed = a->takeCommit();
  }
  ASSERT_TRUE(slowed.has_value());
  for (const auto& d : a->takeDecisions()) details += d.detail + "\n";
  EXPECT_NE(slowed->mode, Mode::kStop) << details;
  EXPECT_NE(details.find("slowing down: answers late"), std::string::npos) << details;
  EXPECT_EQ(a->counters().slowdowns, 1);
  const Trajectory& slow = slowed->trajectory;
  const double start_s = (slowed->start_utime - a->committedStartUtime()) * 1e-6;
  EXPECT_NEAR(start_s, 0.0, 1e-9);
  EXPECT_LT((slow.position(slow.duration()) - before.position(before.duration())).norm(), 1e-6);
  EXPECT_LE(slow.tail(slow.duration() / 2).maxSpeed(), limit * 1.02);
  EXPECT_FALSE(mmh::firstCollisionTime(grid_, slow, 0.0, slow.duration()).has_value());

  // The next rounds ask for no more than the limit (or the speed the vehicle still has).
  std::vector<PlanRequestOut> next;
  for (; t < t1 + 20.0 && next.empty(); t += 0.01) next = fly(*a, t, t);
  ASSERT_FALSE(next.empty());
  const double start_speed = next[0].start.velocity.norm();
  EXPECT_NEAR(next[0].max_speed_mps, std::max(limit, start_speed), 1e-9);

  // latency_window_s without slow answers: full speed again.
  const int64_t later = at(t) + static_cast<int64_t>(params_.latency_window_s * 1e6) + 10'000;
  a->onMapUpdated(grid_, ++map_seq_, later, later);
  EXPECT_EQ(a->latencyBudget().speed_limit_mps, params_.max_vel_mps);
}

// A goal the user put into a tree moves to the nearest free point, and the decision says where.
TEST_F(ArbiterRules, AGoalInsideAnObstacleMovesToTheNearestFreePointAndSaysWhere) {
  putPillar(5.0, 0.0, 0.5);
  params_.policy = Policy::kMmh;
  Arbiter a(params_);
  a.onMapUpdated(grid_, ++map_seq_, at(0), at(0));
  a.setAwareness(true, 0, 1, map_seq_);
  std::string why;
  ASSERT_TRUE(a.setGoal(1, Vector3d(5.0, 0.2, 1.25), at(0), &why)) << why;
  auto decisions = a.takeDecisions();
  ASSERT_EQ(decisions.size(), 1u);
  EXPECT_EQ(decisions[0].outcome, Outcome::kGoalMoved);
  const Vector3d moved = decisions[0].local_target;
  // Nearest free point: out of the pillar (0.5 m) and its margin (inflation_m), on the goal's
  // side of it, no farther than the cell straight out along +y, at the goal's height.
  const Vector3d goal(5.0, 0.2, 1.25);
  EXPECT_TRUE(isClearOf(grid_, moved, params_.inflation_m));
  EXPECT_GT(moved.y(), 0.2);
  EXPECT_LE((moved - goal).norm(),
            (Vector3d(5.05, 0.2 + 0.5 + params_.inflation_m + 0.1, 1.25) - goal).norm());
  EXPECT_GE((moved - goal).norm(), 0.5 + params_.inflation_m - 0.2 - 0.1);
  EXPECT_NEAR(moved.z(), 1.25, 1e-9);
  EXPECT_NE(decisions[0].detail.find("moved"), std::string::npos);
  EXPECT_NE(decisions[0].detail.find("nearest free point"), std::string::npos);
  EXPECT_EQ(a.counters().moved_goals, 1);
  // The rounds plan to the moved goal; the repeated GOAL message is the same goal.
  a.onOdometry(rest(Vector3d(0, 0, 1.2)), at(0));
  auto requests = a.takeRequests();
  ASSERT_EQ(requests.size(), 1u);
  EXPECT_NEAR((requests[0].goal - moved).norm(), 0.0, 1e-12);
  ASSERT_TRUE(a.setGoal(1, Vector3d(5.0, 0.2, 1.25), at(0.5), &why));
  EXPECT_EQ(a.counters().moved_goals, 1);
}

TEST_F(ArbiterRules, AGoalThatANewMapPutsIntoAnObstacleMoves) {
  goal_ = Vector3d(10.0, 0.0, 1.2);  // inside the map window, nothing there yet
  auto a = started(Policy::kMmh);
  a->takeRequests();
  a->takeDecisions();
  putPillar(10.0, 0.0, 0.3);
  a->onMapUpdated(grid_, ++map_seq_, at(0.01), at(0.01));
  auto decisions = a->takeDecisions();
  ASSERT_FALSE(decisions.empty());
  EXPECT_EQ(decisions.front().outcome, Outcome::kGoalMoved);
  EXPECT_TRUE(isClearOf(grid_, decisions.front().local_target, params_.inflation_m));
  EXPECT_LT((decisions.front().local_target - goal_).norm(), params_.goal_relocate_radius_m);
  EXPECT_EQ(a->phase(), Phase::kNewGoal);  // the next round plans to the moved goal
}
