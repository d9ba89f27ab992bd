// The arbiter's policy as pure functions: when to replan (the lazy rules of paper Sec. III.D, or
// fixed-distance replanning for the baselines), which modes to ask (Sec. III.A), which verified
// answer to take, and when to stop instead. Each reads a snapshot of the arbiter's state
// (ReplanView) and its parameters, and changes nothing, so each rule is tested on its own and
// "when does it replan?" has one place to look.
//
// Triggers, in the order nextTrigger tries them, and the modes asked for the full method:
//   goal-changed / initial  a new goal (initial: nothing committed)   FPM if S, else SOM
//   retry                   the last round failed                     the fallback chain's next
//                           (also while unreachable, rarely)          mode: SOM, EAM, a new map
//   collision               a new obstacle on the committed rest       EAM within
//                           (far ones wait for the halfway replan)     emergency_horizon_s, else
//                                                                      as initial
//   halfway                 replan_fraction of the committed flown     FPM if S, else SOM
//                           (not on the way to the goal, unless slow)
//   fixed                   fixed_replan_distance_m flown (baselines)  the policy's one mode
// While stuck (no progress for stuck_after_s, or for stuck_still_s at rest with no mode's answer
// committed) retries come at most every stuck_retry_period_s and one of them backs off to recently
// flown free space; after give_up_s the goal is unreachable: the vehicle holds and retries every
// unreachable_retry_s.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "mmh/arbiter/arbiter_params.hpp"
#include "mmh/arbiter/modes.hpp"
#include "mmh/arbiter/phase.hpp"
#include "mmh/common/trajectory.hpp"

namespace mmh::arbiter {

bool usesAwareness(Policy policy);  // S picks FPM or SOM (mmh, mmh-no-lazy)
bool usesLazyRules(Policy policy);  // halfway replanning (mmh, mmh-no-awareness)

// What the replanning rules read, taken from the arbiter at one moment.
struct ReplanView {
  Phase phase = Phase::kIdle;
  bool has_committed = false;
  bool committed_ends_at_goal = false;
  double committed_elapsed_s = 0.0;  // now minus the committed trajectory's start
  double committed_duration_s = 0.0;
  // The rest-to-rest bound of the committed trajectory's straight length (restToRestTime).
  double committed_bound_s = 0.0;
  // When the committed trajectory repairs the plan before it (a collision round that kept its
  // end): that plan's replan point, in seconds from the committed trajectory's start.
  std::optional<double> repaired_replan_point_s;
  // When it was kept over a later halfway answer: its next replan point (replanPointAfterKeepS).
  std::optional<double> kept_replan_point_s;
  // Set when a newly mapped obstacle threatens the committed trajectory: the time from its
  // detection until the vehicle would reach it (the smallest, if seen again before a round).
  std::optional<double> collision_eta_s;
  bool awareness_safe = true;           // S of the newest AWARENESS for this goal
  double flown_since_last_round_m = 0;  // vehicle travel since the last round started
  double to_goal_m = 0;
  std::optional<Mode> retry_mode;  // the fallback chain's next mode, if it has one now
  double since_last_round_s = 0;   // since the last round started
};

// A committed trajectory slower than slow_plan_ratio x bound_s (the rest-to-rest time of its
// straight length; 0: unknown) is a crawl.
bool isSlowPlan(double duration_s, double bound_s, const ArbiterParams& params);

// Rule (1)'s replan point of a committed trajectory of duration_s, in seconds from its start:
// replan_fraction of it, for a crawl no later than slow_plan_replan_s (a newer map may open a
// faster way) - and, for a repair of the plan before it (same end), no later than that plan's
// own point: repairs must not postpone the replan toward a new local target, or the vehicle
// keeps braking toward the old plan's end.
// A trajectory kept over a later halfway answer replans at kept_replan_point_s instead.
double replanPointS(double duration_s, double bound_s,
                    std::optional<double> repaired_replan_point_s, const ArbiterParams& params,
                    std::optional<double> kept_replan_point_s = std::nullopt);

// Which round (if any) the arbiter starts now.
Trigger nextTrigger(const ReplanView& view, const ArbiterParams& params);

// The modes asked for a round with this trigger; empty when there is nothing to ask.
std::vector<Mode> modesFor(Trigger trigger, const ReplanView& view, const ArbiterParams& params);

// Rule (2) of the lazy policy with its one exception: a collision at `hit_s` on the committed
// trajectory (elapsed_s of it flown) needs a round now, unless the halfway replan (at
// replan_point_s, see replanPointS) comes first and plans with this map before the vehicle gets
// there.
bool collisionNeedsRoundNow(double hit_s, double elapsed_s, double replan_point_s,
                            bool ends_at_goal, const ArbiterParams& params);

// While a stopping trajectory still brakes, retries wait stop_retry_period_s between rounds:
// plans from hard-braking states rarely fit the limits; not when a newly mapped obstacle lies on
// the stop itself (collision_pending), where only an evasive plan can help. While stuck, they
// wait stuck_retry_period_s: the same round on the same map fails the same way.
bool retryThrottled(Trigger trigger, bool braking_in_stop, bool collision_pending, bool stuck,
                    double since_last_round_s, const ArbiterParams& params);

// The stuck detector: what no progress toward the goal for no_progress_s calls for.
enum class StuckResponse {
  kNone,     // making progress
  kBackOff,  // stuck: throttle retries, back off to free space once per stuck_after_s
  kGiveUp,   // unreachable: hold and say why
};
// still_unanswered_s: how long the vehicle has been at rest with no mode's answer committed.
StuckResponse stuckResponse(double no_progress_s, double still_unanswered_s,
                            const ArbiterParams& params);

// Stuck: once per stuck_after_s a retry backs off to recently flown free space, asking every mode
// of the fallback chain at once (the best answer is committed), not only the mode whose turn it
// is, which is often the one that keeps failing in place. since_last_back_off_s is empty before
// the first back-off of the flight.
bool backOffDue(Trigger trigger, StuckResponse stuck, std::optional<double> since_last_back_off_s,
                const ArbiterParams& params);

// EAM on a collision re-optimises the rest of the committed trajectory (its reference), ending
// where it ends, when more than reference_min_remaining_s of it is left after the new start
// (start_s into it) and its end is still clear with the planners' margin.
bool collisionKeepsReference(Trigger trigger, bool end_clear, double start_s, double duration_s,
                             const ArbiterParams& params);

// The goal is reached within goal_tolerance_m, on no trajectory or one that ends there.
bool goalReached(double to_goal_m, bool has_committed, bool committed_ends_at_goal,
                 const ArbiterParams& params);

// Score of a verified answer (lower is better): its estimated time to the goal (the answer
// itself, then the straight rest at full speed) plus score_jerk_weight_s per m^2/s^5 of its jerk
// energy, so that of two answers about as fast the smoother one wins.
double answerScore(const Trajectory& answer, const Eigen::Vector3d& goal,
                   const ArbiterParams& params);

// Lazy rule (1)'s exception: a halfway answer whose estimated arrival (answerScore) is later than
// the committed trajectory's rest by more than halfway_keep_margin_s is not taken while more than
// halfway_keep_min_left_s of that rest is left. The corridor of a fast start can send SOM into a
// U-turn toward a shorter path, a loop that costs seconds while the committed way is still open.
bool keepsCommitted(Trigger trigger, double answer_score_s, double committed_score_s,
                    double committed_left_s, const ArbiterParams& params);

// The kept trajectory's next replan point, in seconds from its start: replan_fraction of the
// rest that was left at the round's start (start_s into it).
double replanPointAfterKeepS(double start_s, double duration_s, const ArbiterParams& params);

// Every reason the arbiter commits a stopping trajectory, decided in one place.
enum class StopCause {
  kStaleMap,        // LOCAL_MAP went stale: planners would plan on an old map
  kStaleOdometry,   // ODOMETRY went stale: the vehicle's state is unknown
  kNoUsableAnswer,  // a round failed with an obstacle ahead on the committed trajectory
  kUnreachable,     // no progress toward the goal for give_up_s: hold
};

struct StopView {
  bool has_committed = false;
  bool committed_is_stop = false;
  double odometry_speed_mps = 0.0;  // measured
  // The fastest the committed trajectory flies from now to its end: one that starts from rest
  // (a plan just committed at a hover) still moves the vehicle.
  double planned_speed_ahead_mps = 0.0;
  bool stopped_for_stale_map = false;
  // The committed trajectory collides with the newest map, or enters unmapped space within the
  // vehicle's reach (Arbiter::unmappedAhead, with stop_decision_margin_s).
  bool danger_ahead = false;
  bool fallback_exhausted = false;  // every mode of the chain failed since the last commit
  // The next retry is held back (retryThrottled: stuck, or braking): the modes left in the chain
  // will not be asked before the danger comes.
  bool retry_held_back = false;
  bool by_deadline = false;  // the failed round was closed by its answer deadline
  // A stop begun stop_decision_margin_s from now would still come to rest clear of the known
  // obstacles: the danger is not yet close, and new maps may still let a mode answer.
  bool stop_can_wait = false;
};

bool shouldStop(StopCause cause, const StopView& view, const ArbiterParams& params);

// How long a round may take on this computer: the replan lead (a new trajectory takes effect
// this long after its request) and the answer deadline, from the answer latencies observed
// (LatencyMonitor). With answers within answer_deadline_s both stay as configured; slower
// answers lengthen the deadline to latency_headroom x their p99 (at most
// max_slowed_answer_deadline_s) and the lead with it, so that answers stop missing a deadline the
// computer cannot meet. Past max_answer_deadline_s the speed limit comes down, so that after the
// longer reaction the vehicle still stops within sensor_range_m.
// Degraded when the budget is above the configured one or LOCAL_MAP arrives older (p99) than
// max_map_age_s; `why` says which.
struct LatencyBudget {
  double answer_latency_p99_s = 0.0;  // what it was made from
  double map_age_p99_s = 0.0;
  double replan_lead_s = 0.0;
  double answer_deadline_s = 0.0;
  double speed_limit_mps = 0.0;  // the planners are asked to fly no faster
  bool degraded = false;
  std::string why;
};
LatencyBudget latencyBudget(double answer_p99_s, double map_age_p99_s, const ArbiterParams& params);

}  // namespace mmh::arbiter
