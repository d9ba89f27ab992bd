#include "mmh/arbiter/replan_rules.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

#include "mmh/common/replan_lead.hpp"
#include "mmh/common/vehicle_limits.hpp"

namespace mmh::arbiter {

bool usesAwareness(Policy policy) {
  return policy == Policy::kMmh || policy == Policy::kMmhNoLazy;
}

bool usesLazyRules(Policy policy) {
  return policy == Policy::kMmh || policy == Policy::kMmhNoAwareness;
}

bool isSlowPlan(double duration_s, double bound_s, const ArbiterParams& params) {
  return bound_s > 0.0 && duration_s > params.slow_plan_ratio * bound_s;
}

double replanPointS(double duration_s, double bound_s,
                    std::optional<double> repaired_replan_point_s, const ArbiterParams& params,
                    std::optional<double> kept_replan_point_s) {
  if (kept_replan_point_s) return *kept_replan_point_s;
  double own_s = params.replan_fraction * duration_s;
  if (isSlowPlan(duration_s, bound_s, params)) own_s = std::min(own_s, params.slow_plan_replan_s);
  return repaired_replan_point_s ? std::min(own_s, *repaired_replan_point_s) : own_s;
}

Trigger nextTrigger(const ReplanView& v, const ArbiterParams& params) {
  if (v.phase == Phase::kNewGoal)
    return v.has_committed ? Trigger::kGoalChanged : Trigger::kInitial;
  if (v.phase == Phase::kUnreachable) {
    return v.retry_mode && v.since_last_round_s >= params.unreachable_retry_s ? Trigger::kRetry
                                                                              : Trigger::kNone;
  }
  // While recovering, the fallback chain goes on: a collision seen again on the next map must not
  // restart it with EAM forever, never reaching SOM or the stop.
  const bool recovering = v.phase == Phase::kRecovering;
  const bool can_retry = recovering && v.retry_mode.has_value();
  if (v.collision_eta_s && !can_retry) return Trigger::kCollision;
  if (recovering) return can_retry ? Trigger::kRetry : Trigger::kNone;
  if (!v.has_committed) return Trigger::kInitial;
  if (usesLazyRules(params.policy)) {
    // Rule (1): past the halfway point, unless this trajectory already ends at the goal at a
    // pace near the bound (a crawl to the goal is replanned as well).
    const bool slow = isSlowPlan(v.committed_duration_s, v.committed_bound_s, params);
    if ((!v.committed_ends_at_goal || slow) &&
        v.committed_elapsed_s > replanPointS(v.committed_duration_s, v.committed_bound_s,
                                             v.repaired_replan_point_s, params,
                                             v.kept_replan_point_s)) {
      return Trigger::kHalfway;
    }
    return Trigger::kNone;
  }
  if (v.flown_since_last_round_m >= params.fixed_replan_distance_m &&
      v.to_goal_m > params.fixed_replan_distance_m) {
    return Trigger::kFixed;
  }
  if (!v.committed_ends_at_goal && v.committed_elapsed_s > v.committed_duration_s) {
    return Trigger::kFixed;
  }
  return Trigger::kNone;
}

std::vector<Mode> modesFor(Trigger trigger, const ReplanView& v, const ArbiterParams& params) {
  const Policy policy = params.policy;
  if (trigger == Trigger::kRetry) {
    if (v.retry_mode) return {*v.retry_mode};
    return {};
  }
  if (policy == Policy::kEgo) return {Mode::kEam};
  if (policy == Policy::kSom) return {Mode::kSom};
  const bool emergency = v.collision_eta_s && *v.collision_eta_s <= params.emergency_horizon_s;
  if (trigger == Trigger::kCollision && (emergency || !usesAwareness(policy))) {
    if (params.parallel_modes != ParallelModes::kNone) return {Mode::kEam, Mode::kSom};
    return {Mode::kEam};
  }
  const bool safe = usesAwareness(policy) && v.awareness_safe;
  if (safe) return {Mode::kFpm};
  if (params.parallel_modes == ParallelModes::kAlways) return {Mode::kSom, Mode::kEam};
  return {Mode::kSom};
}

bool collisionNeedsRoundNow(double hit_s, double elapsed_s, double replan_point_s,
                            bool ends_at_goal, const ArbiterParams& params) {
  const bool halfway_replan_pending =
      usesLazyRules(params.policy) && !ends_at_goal && elapsed_s < replan_point_s;
  return !(params.defer_far_collisions && halfway_replan_pending &&
           hit_s > replan_point_s + params.collision_margin_s);
}

bool retryThrottled(Trigger trigger, bool braking_in_stop, bool collision_pending, bool stuck,
                    double since_last_round_s, const ArbiterParams& params) {
  if (trigger != Trigger::kRetry) return false;
  return (braking_in_stop && !collision_pending &&
          since_last_round_s < params.stop_retry_period_s) ||
         (stuck && since_last_round_s < params.stuck_retry_period_s);
}

StuckResponse stuckResponse(double no_progress_s, double still_unanswered_s,
                            const ArbiterParams& params) {
  if (no_progress_s >= params.give_up_s) return StuckResponse::kGiveUp;
  if (no_progress_s >= params.stuck_after_s) return StuckResponse::kBackOff;
  // Hovering where every answer fails or is refused: the same rounds would fail on until
  // stuck_after_s, so the vehicle is stuck already.
  if (no_progress_s >= params.stuck_still_s && still_unanswered_s >= params.stuck_still_s) {
    return StuckResponse::kBackOff;
  }
  return StuckResponse::kNone;
}

bool backOffDue(Trigger trigger, StuckResponse stuck, std::optional<double> since_last_back_off_s,
                const ArbiterParams& params) {
  return trigger == Trigger::kRetry && stuck != StuckResponse::kNone &&
         (!since_last_back_off_s || *since_last_back_off_s >= params.stuck_after_s);
}

bool collisionKeepsReference(Trigger trigger, bool end_clear, double start_s, double duration_s,
                             const ArbiterParams& params) {
  return trigger == Trigger::kCollision && end_clear &&
         start_s < duration_s - params.reference_min_remaining_s;
}

bool goalReached(double to_goal_m, bool has_committed, bool committed_ends_at_goal,
                 const ArbiterParams& params) {
  return to_goal_m <= params.goal_tolerance_m && (!has_committed || committed_ends_at_goal);
}

double answerScore(const Trajectory& answer, const Eigen::Vector3d& goal,
                   const ArbiterParams& params) {
  const double time_to_goal_s =
      answer.duration() + (goal - answer.position(answer.duration())).norm() / params.max_vel_mps;
  if (params.score_jerk_weight_s <= 0.0) return time_to_goal_s;
  return time_to_goal_s + params.score_jerk_weight_s * answer.jerkEnergy();
}

bool keepsCommitted(Trigger trigger, double answer_score_s, double committed_score_s,
                    double committed_left_s, const ArbiterParams& params) {
  return trigger == Trigger::kHalfway && committed_left_s > params.halfway_keep_min_left_s &&
         answer_score_s > committed_score_s + params.halfway_keep_margin_s;
}

double replanPointAfterKeepS(double start_s, double duration_s, const ArbiterParams& params) {
  return start_s + params.replan_fraction * std::max(0.0, duration_s - start_s);
}

bool shouldStop(StopCause cause, const StopView& v, const ArbiterParams& params) {
  switch (cause) {
    case StopCause::kStaleMap:
      // Once per stale period, and only when the vehicle moves or its trajectory will move it.
      return v.has_committed && !v.stopped_for_stale_map &&
             std::max(v.odometry_speed_mps, v.planned_speed_ahead_mps) > params.stop_min_speed_mps;
    case StopCause::kStaleOdometry:
      // The stop continues the committed trajectory, not the stale odometry.
      return v.has_committed && !v.committed_is_stop &&
             v.planned_speed_ahead_mps > params.stop_min_speed_mps;
    case StopCause::kNoUsableAnswer:
      // Danger ahead and nothing left to try soon (or no time left): brake rather than fly into
      // it - but only once braking cannot wait any longer, so that the modes keep their chance on
      // newer maps. A stop already under way brakes as hard as a new one would.
      return v.danger_ahead && !v.committed_is_stop &&
             (v.fallback_exhausted || v.by_deadline || v.retry_held_back) && !v.stop_can_wait;
    case StopCause::kUnreachable:
      // Holding: no trajectory may move the vehicle on, even one that starts from rest - while
      // the goal is given up, the committed trajectory is no longer checked against new maps.
      return v.has_committed && !v.committed_is_stop &&
             v.planned_speed_ahead_mps > params.stop_min_speed_mps;
  }
  return false;
}

LatencyBudget latencyBudget(double answer_p99_s, double map_age_p99_s,
                            const ArbiterParams& params) {
  LatencyBudget b;
  b.answer_latency_p99_s = answer_p99_s;
  b.map_age_p99_s = map_age_p99_s;
  b.answer_deadline_s = params.answer_deadline_s;
  b.replan_lead_s = params.replan_lead_s;
  b.speed_limit_mps = params.max_vel_mps;
  const double needed_s = params.latency_headroom * answer_p99_s;
  if (needed_s > params.answer_deadline_s) {
    b.answer_deadline_s = std::min(needed_s, params.max_slowed_answer_deadline_s);
    // The lead keeps its configured margin over the deadline (the commit must reach the vehicle).
    b.replan_lead_s =
        replanLeadFor(b.answer_deadline_s, params.replan_lead_s, params.answer_deadline_s);
    // After reacting for the lead and the oldest map it flies on, the vehicle must still stop
    // within what its sensor sees (the start-up check's promise, kept under load): up to
    // max_answer_deadline_s that holds at full speed, past it the speed comes down.
    b.speed_limit_mps =
        std::min(params.max_vel_mps,
                 speedStoppingWithin(params.sensor_range_m, b.replan_lead_s + params.stale_map_s,
                                     params.max_acc_mps2));
    b.degraded = true;
    b.why = "answers late (p99 " + std::to_string(static_cast<int>(answer_p99_s * 1e3)) +
            " ms): deadline " + std::to_string(static_cast<int>(b.answer_deadline_s * 1e3)) +
            " ms, lead " + std::to_string(static_cast<int>(b.replan_lead_s * 1e3)) + " ms";
    if (b.speed_limit_mps < params.max_vel_mps) {
      char speed[32];
      std::snprintf(speed, sizeof speed, "%.2f", b.speed_limit_mps);
      b.why += std::string(", speed lowered to ") + speed + " m/s";
    }
  }
  if (map_age_p99_s > params.max_map_age_s) {
    b.degraded = true;
    b.why += std::string(b.why.empty() ? "" : "; ") + "LOCAL_MAP late (p99 " +
             std::to_string(static_cast<int>(map_age_p99_s * 1e3)) + " ms old)";
  }
  return b;
}

}  // namespace mmh::arbiter
