// The replanning policy as pure functions (replan_rules.hpp): each rule on its own, from a
// hand-made view of the arbiter's state.
#include <gtest/gtest.h>
#include <cmath>

#include "mmh/arbiter/replan_rules.hpp"
#include "mmh/common/minco.hpp"

using namespace mmh::arbiter;

namespace {

// A rest-to-rest minimum-jerk move along x from (0, 0, 1) to (x_end, 0, 1).
mmh::Trajectory restToRest(double x_end, double duration) {
  mmh::MincoJerk m;
  Eigen::Matrix3d head = Eigen::Matrix3d::Zero(), tail = Eigen::Matrix3d::Zero();
  head.col(0) = Eigen::Vector3d(0, 0, 1);
  tail.col(0) = Eigen::Vector3d(x_end, 0, 1);
  m.setConditions(head, tail, 1);
  m.setParameters(Eigen::Matrix3Xd(3, 0), Eigen::VectorXd::Constant(1, duration));
  return m.trajectory();
}

ArbiterParams paramsFor(Policy policy) {
  ArbiterParams p;
  p.policy = policy;
  return p;
}

// Tracking a 10 s trajectory that does not end at the goal, `elapsed_s` of it flown.
ReplanView tracking(double elapsed_s) {
  ReplanView v;
  v.phase = Phase::kTracking;
  v.has_committed = true;
  v.committed_elapsed_s = elapsed_s;
  v.committed_duration_s = 10.0;
  v.committed_bound_s = 8.0;  // its straight length flown at the limits: not a slow plan
  v.to_goal_m = 20.0;
  return v;
}

}  // namespace

TEST(ReplanRules, ANewGoalIsPlannedFirstWhateverElseHappened) {
  ReplanView v = tracking(9.0);
  v.phase = Phase::kNewGoal;
  v.collision_eta_s = 0.5;
  EXPECT_EQ(nextTrigger(v, paramsFor(Policy::kMmh)), Trigger::kGoalChanged);
  v.has_committed = false;
  EXPECT_EQ(nextTrigger(v, paramsFor(Policy::kMmh)), Trigger::kInitial);
}

TEST(ReplanRules, HalfwayRuleFiresPastTheReplanFractionOnly) {
  ArbiterParams p = paramsFor(Policy::kMmh);
  EXPECT_EQ(nextTrigger(tracking(4.9), p), Trigger::kNone);
  EXPECT_EQ(nextTrigger(tracking(5.1), p), Trigger::kHalfway);
  p.replan_fraction = 0.7;
  EXPECT_EQ(nextTrigger(tracking(5.1), p), Trigger::kNone);
  EXPECT_EQ(nextTrigger(tracking(7.1), p), Trigger::kHalfway);
  ReplanView at_goal = tracking(9.0);
  at_goal.committed_ends_at_goal = true;
  EXPECT_EQ(nextTrigger(at_goal, p), Trigger::kNone);
}

TEST(ReplanRules, ASlowTrajectoryToTheGoalIsReplannedToo) {
  ArbiterParams p = paramsFor(Policy::kMmh);
  ReplanView v = tracking(5.1);
  v.committed_ends_at_goal = true;
  EXPECT_EQ(nextTrigger(v, p), Trigger::kNone);          // 10 s against a bound of 8 s: on its way
  v.committed_bound_s = 10.0 / p.slow_plan_ratio - 0.1;  // a crawl to the goal
  EXPECT_EQ(nextTrigger(v, p), Trigger::kHalfway);
  v.committed_elapsed_s = p.slow_plan_replan_s - 0.05;
  EXPECT_EQ(nextTrigger(v, p), Trigger::kNone);  // not before slow_plan_replan_s
  v.committed_elapsed_s = 5.1;
  p.slow_plan_ratio = 3.0;
  EXPECT_EQ(nextTrigger(v, p), Trigger::kNone);
  // The baselines replan after a fixed distance, slow or not.
  v.committed_bound_s = 1.0;
  EXPECT_EQ(nextTrigger(v, paramsFor(Policy::kEgo)), Trigger::kNone);
}

TEST(ReplanRules, ACrawlIsReplannedSoonerThanItsHalfwayPoint) {
  ArbiterParams p = paramsFor(Policy::kMmh);
  p.slow_plan_replan_s = 1.0;
  // A 10 s answer for a way whose straight length takes 2 s: a crawl (an EAM answer slowed down
  // to clear its swerve), replanned 1 s after its commit, not after 5 s.
  EXPECT_TRUE(isSlowPlan(10.0, 2.0, p));
  EXPECT_FALSE(isSlowPlan(10.0, 8.0, p));
  EXPECT_FALSE(isSlowPlan(10.0, 0.0, p));  // bound unknown
  EXPECT_EQ(replanPointS(10.0, 2.0, std::nullopt, p), 1.0);
  EXPECT_EQ(replanPointS(10.0, 8.0, std::nullopt, p), 5.0);
  EXPECT_EQ(replanPointS(1.5, 0.5, std::nullopt, p), 0.75);  // its own halfway comes first
  ReplanView v = tracking(1.1);
  EXPECT_EQ(nextTrigger(v, p), Trigger::kNone);
  v.committed_bound_s = 2.0;
  EXPECT_EQ(nextTrigger(v, p), Trigger::kHalfway);
  v.committed_elapsed_s = 0.9;
  EXPECT_EQ(nextTrigger(v, p), Trigger::kNone);
  // A collision 4 s ahead waits for the crawl's sooner replan (1 s + the 1.5 s margin come
  // first); measured from the halfway point of 5 s it would need a round now.
  EXPECT_TRUE(collisionNeedsRoundNow(4.0, 0.5, 5.0, false, p));
  EXPECT_FALSE(
      collisionNeedsRoundNow(4.0, 0.5, replanPointS(10.0, 2.0, std::nullopt, p), false, p));
}

TEST(ReplanRules, ARepairKeepsTheReplanPointOfThePlanItRepairs) {
  const ArbiterParams p = paramsFor(Policy::kMmh);
  // A collision round re-planned the rest of a plan whose halfway point is 1.5 s into the new
  // 10 s trajectory: rule (1) fires there, not at 5 s.
  ReplanView v = tracking(1.6);
  v.repaired_replan_point_s = 1.5;
  EXPECT_EQ(replanPointS(10.0, 0.0, 1.5, p), 1.5);
  EXPECT_EQ(nextTrigger(v, p), Trigger::kHalfway);
  v.committed_elapsed_s = 1.4;
  EXPECT_EQ(nextTrigger(v, p), Trigger::kNone);
  // A repair answered slower than the plan never moves the point later than its own halfway...
  EXPECT_EQ(replanPointS(10.0, 0.0, 7.0, p), 5.0);
  // ...and a plan whose point has passed is replanned at once.
  v.repaired_replan_point_s = -0.5;
  v.committed_elapsed_s = 0.0;
  EXPECT_EQ(nextTrigger(v, p), Trigger::kHalfway);
  EXPECT_EQ(replanPointS(10.0, 0.0, std::nullopt, p), 5.0);
}

TEST(ReplanRules, AHalfwayAnswerThatArrivesLaterKeepsTheCommittedTrajectory) {
  const ArbiterParams p = paramsFor(Policy::kMmh);  // margin 0.5 s, at least 2 s left
  // Later by more than the margin, with more than 2 s of the committed rest left: kept.
  EXPECT_TRUE(keepsCommitted(Trigger::kHalfway, 17.9, 9.4, 3.3, p));
  // Later by less than the margin, or sooner: taken.
  EXPECT_FALSE(keepsCommitted(Trigger::kHalfway, 9.8, 9.4, 3.3, p));
  EXPECT_FALSE(keepsCommitted(Trigger::kHalfway, 8.0, 9.4, 3.3, p));
  // Too little of the committed rest left (the vehicle would brake to its end): taken.
  EXPECT_FALSE(keepsCommitted(Trigger::kHalfway, 17.9, 9.4, 1.9, p));
  // Only the halfway replan, never a round that answers a danger or a new goal.
  for (Trigger t : {Trigger::kCollision, Trigger::kRetry, Trigger::kInitial, Trigger::kGoalChanged,
                    Trigger::kFixed})
    EXPECT_FALSE(keepsCommitted(t, 17.9, 9.4, 3.3, p));
}

TEST(ReplanRules, AKeptTrajectoryIsReplannedHalfwayThroughItsRest) {
  const ArbiterParams p = paramsFor(Policy::kMmh);
  // Kept at 5 s into a 10 s trajectory: the next halfway replan at 7.5 s, not at once.
  const double point = replanPointAfterKeepS(5.0, 10.0, p);
  EXPECT_DOUBLE_EQ(point, 7.5);
  ReplanView v = tracking(5.1);
  v.kept_replan_point_s = point;
  EXPECT_EQ(nextTrigger(v, p), Trigger::kNone);
  v.committed_elapsed_s = 7.6;
  EXPECT_EQ(nextTrigger(v, p), Trigger::kHalfway);
  // The kept point overrides a repaired plan's earlier one.
  EXPECT_EQ(replanPointS(10.0, 0.0, 1.5, p, 7.5), 7.5);
}

TEST(ReplanRules, BaselinesReplanAfterAFixedDistance) {
  const ArbiterParams p = paramsFor(Policy::kEgo);
  ReplanView v = tracking(1.0);
  v.flown_since_last_round_m = 1.4;
  EXPECT_EQ(nextTrigger(v, p), Trigger::kNone);
  v.flown_since_last_round_m = 1.5;
  EXPECT_EQ(nextTrigger(v, p), Trigger::kFixed);
  v.to_goal_m = 1.0;  // the last stretch is flown on the plan that reaches the goal
  EXPECT_EQ(nextTrigger(v, p), Trigger::kNone);
  EXPECT_EQ(nextTrigger(tracking(10.5), p), Trigger::kFixed);  // ran out of trajectory
}

TEST(ReplanRules, RecoveringRetriesWithTheChainsModeEvenWhenACollisionIsSeenAgain) {
  ReplanView v = tracking(1.0);
  v.phase = Phase::kRecovering;
  v.collision_eta_s = 1.0;
  v.retry_mode = Mode::kEam;
  const ArbiterParams p = paramsFor(Policy::kMmh);
  EXPECT_EQ(nextTrigger(v, p), Trigger::kRetry);
  EXPECT_EQ(modesFor(Trigger::kRetry, v, p), std::vector<Mode>{Mode::kEam});
  v.retry_mode.reset();  // chain exhausted, no new map: only a new collision starts a round
  EXPECT_EQ(nextTrigger(v, p), Trigger::kCollision);
  v.collision_eta_s.reset();
  EXPECT_EQ(nextTrigger(v, p), Trigger::kNone);
  EXPECT_TRUE(modesFor(Trigger::kRetry, v, p).empty());
}

TEST(ReplanRules, AwarenessPicksFpmOrSom) {
  const ArbiterParams p = paramsFor(Policy::kMmh);
  ReplanView v = tracking(6.0);
  v.awareness_safe = true;
  EXPECT_EQ(modesFor(Trigger::kHalfway, v, p), std::vector<Mode>{Mode::kFpm});
  v.awareness_safe = false;
  EXPECT_EQ(modesFor(Trigger::kHalfway, v, p), std::vector<Mode>{Mode::kSom});
  v.awareness_safe = true;  // without awareness, never FPM
  EXPECT_EQ(modesFor(Trigger::kHalfway, v, paramsFor(Policy::kMmhNoAwareness)),
            std::vector<Mode>{Mode::kSom});
}

TEST(ReplanRules, NearCollisionsAskEamFarOnesTheAwarenessMode) {
  ArbiterParams p = paramsFor(Policy::kMmh);
  ReplanView v = tracking(1.0);
  v.awareness_safe = false;
  v.collision_eta_s = p.emergency_horizon_s - 0.1;
  EXPECT_EQ(modesFor(Trigger::kCollision, v, p), std::vector<Mode>{Mode::kEam});
  v.collision_eta_s = p.emergency_horizon_s + 0.1;
  EXPECT_EQ(modesFor(Trigger::kCollision, v, p), std::vector<Mode>{Mode::kSom});
  p.parallel_modes = ParallelModes::kCollision;
  v.collision_eta_s = 0.5;
  EXPECT_EQ(modesFor(Trigger::kCollision, v, p), (std::vector<Mode>{Mode::kEam, Mode::kSom}));
  p.parallel_modes = ParallelModes::kAlways;
  EXPECT_EQ(modesFor(Trigger::kHalfway, v, p), (std::vector<Mode>{Mode::kSom, Mode::kEam}));
}

TEST(ReplanRules, SingleModeBaselinesAskTheirModeForEveryTrigger) {
  const ReplanView v = tracking(1.0);
  for (Trigger t : {Trigger::kInitial, Trigger::kCollision, Trigger::kFixed}) {
    EXPECT_EQ(modesFor(t, v, paramsFor(Policy::kEgo)), std::vector<Mode>{Mode::kEam});
    EXPECT_EQ(modesFor(t, v, paramsFor(Policy::kSom)), std::vector<Mode>{Mode::kSom});
  }
}

TEST(ReplanRules, CollisionsBeyondTheHalfwayReplanWaitForIt) {
  ArbiterParams p = paramsFor(Policy::kMmh);
  // 10 s trajectory, 1 s flown: the halfway replan comes at 5 s.
  EXPECT_TRUE(collisionNeedsRoundNow(5.0 + p.collision_margin_s - 0.1, 1.0, 5.0, false, p));
  EXPECT_FALSE(collisionNeedsRoundNow(5.0 + p.collision_margin_s + 0.1, 1.0, 5.0, false, p));
  EXPECT_TRUE(collisionNeedsRoundNow(9.0, 1.0, 5.0, true, p));   // no halfway replan comes
  EXPECT_TRUE(collisionNeedsRoundNow(9.0, 5.5, 5.0, false, p));  // it came already
  p.defer_far_collisions = false;
  EXPECT_TRUE(collisionNeedsRoundNow(9.0, 1.0, 5.0, false, p));
  EXPECT_TRUE(collisionNeedsRoundNow(9.0, 1.0, 5.0, false, paramsFor(Policy::kEgo)));
}

TEST(ReplanRules, RetriesWhileAStopBrakesWaitTheirPeriod) {
  const ArbiterParams p = paramsFor(Policy::kMmh);
  EXPECT_TRUE(retryThrottled(Trigger::kRetry, true, false, false, p.stop_retry_period_s / 2, p));
  EXPECT_FALSE(retryThrottled(Trigger::kRetry, true, false, false, p.stop_retry_period_s * 2, p));
  EXPECT_FALSE(retryThrottled(Trigger::kCollision, true, false, false, 0.0, p));
  EXPECT_FALSE(retryThrottled(Trigger::kRetry, false, false, false, 0.0, p));
}

TEST(ReplanRules, ANewObstacleOnTheStopItselfIsRetriedAtOnce) {
  const ArbiterParams p = paramsFor(Policy::kMmh);
  EXPECT_FALSE(retryThrottled(Trigger::kRetry, true, true, false, 0.0, p));
  // Stuck, the same map fails the same way: that period still holds.
  EXPECT_TRUE(retryThrottled(Trigger::kRetry, true, true, true, p.stuck_retry_period_s / 2, p));
}

TEST(ReplanRules, RetriesWhileStuckComeAtMostEveryStuckRetryPeriod) {
  const ArbiterParams p = paramsFor(Policy::kMmh);
  EXPECT_TRUE(retryThrottled(Trigger::kRetry, false, false, true, p.stuck_retry_period_s / 2, p));
  EXPECT_FALSE(
      retryThrottled(Trigger::kRetry, false, false, true, p.stuck_retry_period_s * 1.1, p));
}

TEST(ReplanRules, NoProgressMeansStuckThenUnreachable) {
  const ArbiterParams p = paramsFor(Policy::kMmh);
  EXPECT_EQ(stuckResponse(p.stuck_after_s - 0.1, 0.0, p), StuckResponse::kNone);
  EXPECT_EQ(stuckResponse(p.stuck_after_s + 0.1, 0.0, p), StuckResponse::kBackOff);
  EXPECT_EQ(stuckResponse(p.give_up_s + 0.1, 0.0, p), StuckResponse::kGiveUp);
}

TEST(ReplanRules, AVehicleAtRestThatNoModeMovesIsStuckSooner) {
  const ArbiterParams p = paramsFor(Policy::kMmh);
  ASSERT_LT(p.stuck_still_s, p.stuck_after_s);
  const double still = p.stuck_still_s + 0.1;
  EXPECT_EQ(stuckResponse(still, still, p), StuckResponse::kBackOff);
  // Moving, or an answer committed since it came to rest: only the progress clock counts.
  EXPECT_EQ(stuckResponse(still, 0.0, p), StuckResponse::kNone);
  EXPECT_EQ(stuckResponse(still, p.stuck_still_s - 0.1, p), StuckResponse::kNone);
  // Progress made just before it came to rest: not yet.
  EXPECT_EQ(stuckResponse(p.stuck_still_s - 0.1, still, p), StuckResponse::kNone);
  EXPECT_EQ(stuckResponse(p.give_up_s + 0.1, still, p), StuckResponse::kGiveUp);
}

TEST(ReplanRules, AStuckRetryBacksOffOncePerStuckPeriod) {
  const ArbiterParams p = paramsFor(Policy::kMmh);
  EXPECT_FALSE(backOffDue(Trigger::kRetry, StuckResponse::kNone, std::nullopt, p));
  EXPECT_TRUE(backOffDue(Trigger::kRetry, StuckResponse::kBackOff, std::nullopt, p));
  EXPECT_FALSE(backOffDue(Trigger::kRetry, StuckResponse::kBackOff, p.stuck_after_s - 0.1, p));
  EXPECT_TRUE(backOffDue(Trigger::kRetry, StuckResponse::kBackOff, p.stuck_after_s + 0.1, p));
  // An unreachable goal's retries still back off.
  EXPECT_TRUE(backOffDue(Trigger::kRetry, StuckResponse::kGiveUp, p.stuck_after_s + 0.1, p));
  // Only retries: a collision or a new goal plans toward the goal.
  EXPECT_FALSE(backOffDue(Trigger::kCollision, StuckResponse::kBackOff, std::nullopt, p));
  EXPECT_FALSE(backOffDue(Trigger::kGoalChanged, StuckResponse::kBackOff, std::nullopt, p));
}

TEST(ReplanRules, AnUnreachableGoalIsRetriedOnlyEveryUnreachableRetryPeriod) {
  const ArbiterParams p = paramsFor(Policy::kMmh);
  ReplanView v = tracking(1.0);
  v.phase = Phase::kUnreachable;
  v.collision_eta_s = 0.5;  // not even a collision starts a round
  v.retry_mode = Mode::kSom;
  v.since_last_round_s = p.unreachable_retry_s - 0.1;
  EXPECT_EQ(nextTrigger(v, p), Trigger::kNone);
  v.since_last_round_s = p.unreachable_retry_s + 0.1;
  EXPECT_EQ(nextTrigger(v, p), Trigger::kRetry);
  v.retry_mode.reset();
  EXPECT_EQ(nextTrigger(v, p), Trigger::kNone);
}

TEST(ReplanRules, EamKeepsTheReferenceOnlyWithEnoughOfItLeftAndAClearEnd) {
  const ArbiterParams p = paramsFor(Policy::kMmh);
  EXPECT_TRUE(collisionKeepsReference(Trigger::kCollision, true, 5.0, 10.0, p));
  EXPECT_FALSE(collisionKeepsReference(Trigger::kCollision, false, 5.0, 10.0, p));
  EXPECT_FALSE(collisionKeepsReference(Trigger::kCollision, true, 9.9, 10.0, p));
  EXPECT_FALSE(collisionKeepsReference(Trigger::kHalfway, true, 5.0, 10.0, p));
}

TEST(ReplanRules, GoalIsReachedOnlyOnATrajectoryThatEndsThere) {
  const ArbiterParams p = paramsFor(Policy::kMmh);
  EXPECT_TRUE(goalReached(0.2, true, true, p));
  EXPECT_TRUE(goalReached(0.2, false, false, p));
  EXPECT_FALSE(goalReached(0.2, true, false, p));  // passing through on the way elsewhere
  EXPECT_FALSE(goalReached(0.5, true, true, p));
}

TEST(ReplanRules, ScorePrefersTheEarlierArrival) {
  const ArbiterParams p = paramsFor(Policy::kMmh);
  const Eigen::Vector3d goal(30, 0, 1);
  // 10 m in 6 s + 20 m at 3 m/s = 12.67 s, against 5 m in 3 s + 25 m at 3 m/s = 11.33 s.
  EXPECT_NEAR(answerScore(restToRest(10, 6), goal, p), 6.0 + 20.0 / 3.0, 1e-9);
  EXPECT_LT(answerScore(restToRest(5, 3), goal, p), answerScore(restToRest(10, 6), goal, p));
}

TEST(ReplanRules, ScoreWithJerkWeightPrefersTheSmootherOfTwoAboutAsFastAnswers) {
  ArbiterParams p = paramsFor(Policy::kMmh);
  const Eigen::Vector3d goal(30, 0, 1);
  const mmh::Trajectory hard = restToRest(5, 2.5), smooth = restToRest(5, 3.0);
  // Off (the default): the earlier arrival wins.
  ASSERT_EQ(p.score_jerk_weight_s, 0.0);
  EXPECT_LT(answerScore(hard, goal, p), answerScore(smooth, goal, p));
  // A rest-to-rest minimum-jerk move of d metres in T seconds has a jerk energy of 720 d^2 / T^5:
  // 230.4 m^2/s^5 in 2.5 s, 74.07 in 3 s. At 0.01 s per m^2/s^5, 0.5 s later but 1.56 s
  // smoother.
  p.score_jerk_weight_s = 0.01;
  EXPECT_NEAR(answerScore(hard, goal, p), 2.5 + 25.0 / 3.0 + 0.01 * 720.0 * 25.0 / std::pow(2.5, 5),
              1e-6);
  EXPECT_NEAR(answerScore(smooth, goal, p), 3.0 + 25.0 / 3.0 + 0.01 * 720.0 * 25.0 / 243.0, 1e-6);
  EXPECT_LT(answerScore(smooth, goal, p), answerScore(hard, goal, p));
  // A much slower answer is not made up for by smoothness: 5 m in 6 s against 2.5 s.
  EXPECT_LT(answerScore(hard, goal, p), answerScore(restToRest(5, 6.0), goal, p));
}

TEST(ReplanRules, EveryStopHasItsCondition) {
  const ArbiterParams p = paramsFor(Policy::kMmh);
  StopView moving;
  moving.has_committed = true;
  moving.odometry_speed_mps = 2.0;
  moving.planned_speed_ahead_mps = 2.0;
  EXPECT_TRUE(shouldStop(StopCause::kStaleMap, moving, p));
  StopView once = moving;
  once.stopped_for_stale_map = true;
  EXPECT_FALSE(shouldStop(StopCause::kStaleMap, once, p));
  StopView still = moving;
  still.odometry_speed_mps = still.planned_speed_ahead_mps = 0.01;
  EXPECT_FALSE(shouldStop(StopCause::kStaleMap, still, p));
  EXPECT_FALSE(shouldStop(StopCause::kStaleOdometry, still, p));
  EXPECT_FALSE(shouldStop(StopCause::kUnreachable, still, p));
  EXPECT_TRUE(shouldStop(StopCause::kStaleOdometry, moving, p));
  EXPECT_TRUE(shouldStop(StopCause::kUnreachable, moving, p));
  // At rest now on a trajectory that will move it (a plan just committed at a hover): a stale
  // stream or a goal given up must hold it there, or it flies off on a path nobody checks.
  StopView about_to_leave = still;
  about_to_leave.planned_speed_ahead_mps = 1.5;
  EXPECT_TRUE(shouldStop(StopCause::kStaleMap, about_to_leave, p));
  EXPECT_TRUE(shouldStop(StopCause::kStaleOdometry, about_to_leave, p));
  EXPECT_TRUE(shouldStop(StopCause::kUnreachable, about_to_leave, p));

  StopView failed = moving;
  failed.danger_ahead = true;
  EXPECT_FALSE(shouldStop(StopCause::kNoUsableAnswer, failed, p));  // modes left, time left
  failed.fallback_exhausted = true;
  EXPECT_TRUE(shouldStop(StopCause::kNoUsableAnswer, failed, p));
  failed.stop_can_wait = true;  // a later stop still ends clear: the modes get newer maps
  EXPECT_FALSE(shouldStop(StopCause::kNoUsableAnswer, failed, p));
  failed.stop_can_wait = false;
  failed.fallback_exhausted = false;
  failed.by_deadline = true;
  EXPECT_TRUE(shouldStop(StopCause::kNoUsableAnswer, failed, p));
  failed.by_deadline = false;
  failed.retry_held_back = true;  // stuck: the next mode would be asked too late
  EXPECT_TRUE(shouldStop(StopCause::kNoUsableAnswer, failed, p));
  failed.committed_is_stop = true;  // already braking
  EXPECT_FALSE(shouldStop(StopCause::kNoUsableAnswer, failed, p));
  failed.committed_is_stop = false;
  failed.danger_ahead = false;
  EXPECT_FALSE(shouldStop(StopCause::kNoUsableAnswer, failed, p));

  EXPECT_TRUE(shouldStop(StopCause::kUnreachable, moving, p));
  EXPECT_FALSE(shouldStop(StopCause::kUnreachable, still, p));
}
