#include "mmh/arbiter/arbiter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "mmh/arbiter/goal_placement.hpp"
#include "mmh/arbiter/local_target.hpp"
#include "mmh/arbiter/retrace.hpp"
#include "mmh/common/collision_check.hpp"
#include "mmh/common/geofence.hpp"
#include "mmh/common/stopping_trajectory.hpp"
#include "mmh/common/vehicle_limits.hpp"

namespace mmh::arbiter {
namespace {

constexpr double kUs = 1e-6;                 // seconds per microsecond
constexpr double kSameGoalDistanceM = 1e-6;  // a goal message repeated, not a moved goal

}  // namespace

// The backup stop's search: bisection steps for the latest clear stop within the horizon, and
// as many again for the latest point before it from which the whole backup is clear. Each step
// walks the backup, so both bound the time the arbiter spends on a failed round: a slow path
// searched 0.1 s at a time to its end once held it for 1.3 s while the vehicle flew on.
constexpr int kBackupSearchSteps = 6;
constexpr double kBackupHorizonS = 3.0;

// Recently flown positions, 20 per second over the last 20 s, are the back-off candidates.
constexpr double kBackOffHistoryS = 20.0;
constexpr double kBackOffSamplePeriodS = 0.05;
// The way back along them keeps points this far apart (hovering leaves many on one spot).
constexpr double kRetraceSpacingM = 0.1;

Arbiter::Arbiter(const ArbiterParams& params)
    : params_(params),
      chain_(params.policy),
      progress_(params.progress_min_step_m, kBackOffHistoryS, kBackOffSamplePeriodS,
                params.progress_new_ground_m),
      latency_(params.latency_window_s),
      budget_(mmh::arbiter::latencyBudget(0.0, 0.0, params)) {}

void Arbiter::updateLatencyBudget() {
  latency_.expire(now_);
  LatencyBudget next = mmh::arbiter::latencyBudget(latency_.worstAnswerLatency(0.99),
                                                   latency_.mapAge(0.99), params_);
  if (next.degraded && !budget_.degraded) ++counters_.degraded_periods;
  budget_ = std::move(next);
}

bool Arbiter::mapStale(int64_t now) const {
  return map_seq_ == 0 || (now - map_utime_) * kUs > params_.stale_map_s;
}

bool Arbiter::odometryStale(int64_t now) const {
  return odometry_ && (now - odometry_utime_) * kUs > params_.stale_odometry_s;
}

bool Arbiter::setGoal(int64_t goal_id, const Eigen::Vector3d& goal, int64_t now, std::string* why) {
  now_ = std::max(now_, now);
  if (hasGoal() && goal_id == goal_.id && (goal - goal_.requested).norm() < kSameGoalDistanceM) {
    evaluate(now_);  // its clock may show that ODOMETRY stopped
    return true;
  }
  auto refuse = [&](const std::string& text) {
    ++counters_.rejected_goals;
    if (why) *why = text;
    DecisionOut d;
    d.outcome = Outcome::kRejected;
    d.local_target = goal;
    d.detail = "goal " + std::to_string(goal_id) + " refused: " + text;
    pushDecision(d);
    return false;
  };
  if (!goal.allFinite()) return refuse("not finite");
  const std::string outside = geofenceViolation(geofence(), goal, "it");
  if (!outside.empty()) return refuse(outside);
  GoalPlacement placement;
  placement.ok = true;
  placement.position = goal;
  if (grid_) {
    placement = placeGoal(*grid_, goal, params_.inflation_m, params_.goal_relocate_radius_m,
                          params_.geofence_min_m, params_.geofence_max_m);
    if (!placement.ok) return refuse(placement.why);
  }
  goal_ = Goal{goal_id, placement.position, goal};
  phase_ = Phase::kNewGoal;
  chain_.reset();
  progress_.restart(now_);
  if (placement.moved) reportGoalMoved(placement.why);
  evaluate(now_);
  return true;
}

void Arbiter::relocateGoalIfBlocked() {
  if (!hasGoal() || !grid_ || isClearOf(*grid_, goal_.position, params_.inflation_m)) return;
  const GoalPlacement placement =
      placeGoal(*grid_, goal_.requested, params_.inflation_m, params_.goal_relocate_radius_m,
                params_.geofence_min_m, params_.geofence_max_m);
  // No free point near it: the rounds fail and the stuck detector gives up in time.
  if (!placement.ok || (placement.position - goal_.position).norm() < kSameGoalDistanceM) return;
  goal_.position = placement.position;
  if (phase_ != Phase::kIdle) phase_ = Phase::kNewGoal;
  chain_.reset();
  progress_.restart(now_);
  reportGoalMoved(placement.why);
}

void Arbiter::reportGoalMoved(const std::string& why) {
  ++counters_.moved_goals;
  DecisionOut d;
  d.outcome = Outcome::kGoalMoved;
  d.local_target = goal_.position;
  d.detail = "goal " + std::to_string(goal_.id) + ": " + why;
  pushDecision(d);
}

void Arbiter::setAwareness(bool safe, int8_t reason, int64_t goal_id, int64_t /*map_seq*/) {
  awareness_ = Awareness{safe, reason, goal_id};
}

void Arbiter::onMapUpdated(const VoxelGrid& grid, int64_t map_seq, int64_t map_utime, int64_t now) {
  grid_ = &grid;
  map_seq_ = map_seq;
  map_utime_ = map_utime;
  now_ = std::max(now_, now);
  latency_.onMapAge((now_ - map_utime) * kUs, now_);
  updateLatencyBudget();
  if (stopped_for_stale_map_ && !mapStale(now_)) stopped_for_stale_map_ = false;
  if (phase_ != Phase::kReached) relocateGoalIfBlocked();
  // Rule (2): a newly mapped obstacle on the rest of the committed trajectory.
  // And its safety twin: unmapped space coming within the vehicle's reach, where a stop could
  // no longer end in space the sensor has seen.
  double eta_s = 0.0;
  if (hasCommitted() && !round_ && phase_ != Phase::kReached) {
    std::optional<double> threat_s;
    UnmappedCell unmapped;
    if (collisionThreat(now_, &eta_s)) {
      threat_s = eta_s;
      threat_note_.clear();
    } else if ((threat_s = unmappedAhead(now_, params_.stop_decision_margin_s, &unmapped))) {
      threat_note_ = "unmapped space on the committed trajectory within stopping reach, " +
                     describeUnmappedCell(unmapped) + "; ";
    }
    if (threat_s) {
      collision_eta_s_ = collision_eta_s_ ? std::min(*collision_eta_s_, *threat_s) : *threat_s;
      if (!threat_seen_utime_ && dangerOnFlownTrajectory(now_)) threat_seen_utime_ = map_utime;
    } else {
      // The danger a failed round left unanswered is gone from this map: no commit answers it.
      threat_seen_utime_.reset();
    }
  }
  evaluate(now_);
}

void Arbiter::onOdometry(const KinematicState& state, int64_t now) {
  odometry_ = state;
  if (state.velocity.norm() > params_.braking_speed_mps) {
    still_since_utime_.reset();
  } else if (!still_since_utime_) {
    still_since_utime_ = now;
  }
  odometry_utime_ = std::max(odometry_utime_, now);
  now_ = std::max(now_, now);
  if (hasGoal()) progress_.observe(now_, state.position, (state.position - goal_.position).norm());
  if (stopped_for_stale_odometry_ && !odometryStale(now_)) stopped_for_stale_odometry_ = false;
  evaluate(now_);
}

void Arbiter::onAnswer(const ModeAnswer& answer, int64_t now) {
  now_ = std::max(now_, now);
  if (answer.mode >= Mode::kFpm && answer.mode <= Mode::kEam) {
    ++counters_.iterations[modeIndex(answer.mode)];
  }
  // Late answers too: they are what the budget must learn from.
  if (latency_.onAnswer(answer.request_id, now) >= 0.0) updateLatencyBudget();
  if (!round_) {
    ++counters_.late_answers;
    return;
  }
  bool known = false;
  for (const auto& r : round_->requests) {
    known |= (r.request_id == answer.request_id && r.mode == answer.mode);
  }
  bool duplicate = false;
  for (const auto& a : round_->answers) duplicate |= (a.request_id == answer.request_id);
  if (!known || duplicate) {
    ++counters_.late_answers;
    return;
  }
  round_->answers.push_back(answer);
  if (round_->answers.size() == round_->requests.size()) decide(now_, false);
}

void Arbiter::onClock(int64_t now) {
  now_ = std::max(now_, now);
  evaluate(now_);
}

Eigen::Vector3d Arbiter::vehiclePosition() const {
  return odometry_ ? odometry_->position : Eigen::Vector3d::Zero();
}

int64_t Arbiter::takeOverUtime(int64_t now) const {
  const int64_t after_lead = now + static_cast<int64_t>(budget_.replan_lead_s * 1e6);
  // The lead may have shrunk since the committed trajectory was placed; it has been sent, so
  // what follows it can only take over from its start on.
  return hasCommitted() ? std::max(after_lead, committed_.start_utime) : after_lead;
}

const Trajectory& Arbiter::flownTrajectory() const {
  return committed_.backup ? *committed_.backup : committed_.trajectory;
}

KinematicState Arbiter::stateAt(int64_t utime) const {
  if (hasCommitted()) return flownTrajectory().state((utime - committed_.start_utime) * kUs);
  KinematicState hold;
  hold.position = vehiclePosition();
  return hold;
}

bool Arbiter::collisionAhead(int64_t now) const {
  if (!grid_ || !hasCommitted()) return false;
  const Trajectory& t = committed_.trajectory;
  const double t0 = std::max(0.0, (now - committed_.start_utime) * kUs);
  return committedCollisionTime(t0, t.duration()).has_value();
}

std::optional<double> Arbiter::committedCollisionTime(double from_s, double to_s) const {
  const Trajectory& t = committed_.trajectory;
  if (committed_.retrace) {
    for (double s = from_s; s <= to_s; s += params_.check_step_s) {
      if (!keepsEscapeDistance(*grid_, t.position(s), committed_.escape_min_distance_m)) return s;
    }
    return std::nullopt;
  }
  const double escape_end = std::min(to_s, committed_.escape_until_s);
  if (from_s < escape_end) {
    if (const auto hit =
            firstCollisionTime(*grid_, t, from_s, escape_end, CollisionLayer::kOccupied))
      return hit;
    if (const auto deeper =
            firstEscapeTooDeep(*grid_, t, from_s, escape_end, params_.escape_step_s,
                               committed_.escape_min_distance_m, params_.escape_depth_tolerance_m))
      return deeper;
    from_s = escape_end;
  }
  return firstCollisionTime(*grid_, t, from_s, to_s);
}

double Arbiter::stopTouchDistance() const {
  return params_.vehicle_radius_m + (grid_ ? 0.5 * grid_->resolution() : 0.0);
}

StopCondition Arbiter::noHiddenFaceBeside() const {
  if (!grid_ || params_.hidden_face_m <= 0.0) return {};
  return [this](const Trajectory& stop) { return !touchesHiddenFace(stop, *grid_, params_); };
}

Geofence Arbiter::fenceFrom(const Eigen::Vector3d& start) const {
  return fenceForStart(geofence(), start, params_.geofence_tolerance_m);
}

Trajectory Arbiter::stopAlongCommitted(double t0_s, bool may_swerve) const {
  const Geofence fence = fenceFrom(flownTrajectory().position(t0_s));
  return chooseStoppingTrajectory(grid_, flownTrajectory(), t0_s, params_.max_acc_mps2,
                                  params_.max_vel_mps, params_.check_inflation_m,
                                  stopTouchDistance(), may_swerve, &fence, noHiddenFaceBeside());
}

bool Arbiter::stopCanWait(int64_t now) const {
  if (!grid_ || !hasCommitted() || params_.stop_decision_margin_s <= 0.0) return false;
  const Trajectory& t = committed_.trajectory;
  const double later_s =
      (now - committed_.start_utime) * kUs + budget_.replan_lead_s + params_.stop_decision_margin_s;
  if (later_s >= t.duration()) return false;
  if (committedCollisionTime(std::max(0.0, (now - committed_.start_utime) * kUs), later_s)) {
    return false;
  }
  // Only a stop that brakes counts: waiting is no reason to swerve farther.
  const Trajectory later_stop = stopAlongCommitted(later_s, false);
  if (firstCollisionTime(*grid_, later_stop, 0.0, later_stop.duration())) return false;
  // Nor may waiting carry the stop farther into unmapped space than a stop now would go.
  const Trajectory stop_now =
      stopAlongCommitted((now - committed_.start_utime) * kUs + budget_.replan_lead_s, false);
  const double limit_m = params_.check_inflation_m;
  return assessStop(*grid_, later_stop, limit_m).unknown_m <=
         assessStop(*grid_, stop_now, limit_m).unknown_m + grid_->resolution();
}

bool Arbiter::dangerOnFlownTrajectory(int64_t now) const {
  if (!committed_.backup) return true;
  const Trajectory& backup = *committed_.backup;
  const double elapsed = std::max(0.0, (now - committed_.start_utime) * kUs);
  return firstCollisionTime(*grid_, backup, elapsed, backup.duration()).has_value() ||
         firstUnknownWithinReach(backup, elapsed,
                                 budget_.replan_lead_s + params_.stop_decision_margin_s, *grid_,
                                 params_)
             .has_value();
}

std::optional<double> Arbiter::unmappedAhead(int64_t now, double extra_s,
                                             UnmappedCell* where) const {
  // A retrace runs where the vehicle has flown: mapped as it went, or passed by the airframe.
  if (!grid_ || !hasCommitted() || committed_.mode == Mode::kStop || committed_.retrace)
    return std::nullopt;
  const double elapsed = std::max(0.0, (now - committed_.start_utime) * kUs);
  const auto at = firstUnknownWithinReach(committed_.trajectory, elapsed,
                                          budget_.replan_lead_s + extra_s, *grid_, params_, where);
  if (!at) return std::nullopt;
  return *at - elapsed;
}

bool Arbiter::collisionThreat(int64_t now, double* eta_s) const {
  if (!grid_ || !hasCommitted()) return false;
  const Trajectory& t = committed_.trajectory;
  const double elapsed = std::max(0.0, (now - committed_.start_utime) * kUs);
  const auto hit = committedCollisionTime(elapsed, t.duration());
  if (!hit) return false;
  *eta_s = *hit - elapsed;
  const double replan_point_s = replanPointS(t.duration(), committed_.bound_s,
                                             repairedReplanPointS(), params_, keptReplanPointS());
  return collisionNeedsRoundNow(*hit, elapsed, replan_point_s, committed_.ends_at_goal, params_);
}

ReplanView Arbiter::replanView(int64_t now) const {
  ReplanView v;
  v.phase = phase_;
  v.has_committed = hasCommitted();
  v.committed_ends_at_goal = committed_.ends_at_goal;
  v.committed_elapsed_s = (now - committed_.start_utime) * kUs;
  v.committed_duration_s = committed_.trajectory.duration();
  v.committed_bound_s = committed_.bound_s;
  v.repaired_replan_point_s = repairedReplanPointS();
  v.kept_replan_point_s = keptReplanPointS();
  v.collision_eta_s = collision_eta_s_;
  v.awareness_safe = awareness_ ? awareness_->safe : true;
  v.flown_since_last_round_m = (vehiclePosition() - last_round_position_).norm();
  v.to_goal_m = (vehiclePosition() - goal_.position).norm();
  v.retry_mode = chain_.next(map_seq_);
  // A danger newly mapped on a stop still braking is an emergency: the chain starts again with
  // EAM, which repairs the way the vehicle is on; SOM from a hard-braking state rarely keeps the
  // limits, and its failure cost the answer a map period.
  const auto& chain = chain_.modes();
  const bool braking_stop = committed_.mode == Mode::kStop && odometry_ &&
                            odometry_->velocity.norm() > params_.braking_speed_mps;
  if (v.retry_mode && braking_stop && collision_eta_s_ && chain_.exhausted() &&
      std::find(chain.begin(), chain.end(), Mode::kEam) != chain.end()) {
    v.retry_mode = Mode::kEam;
  }
  v.since_last_round_s = (now - last_round_utime_) * kUs;
  return v;
}

StopView Arbiter::stopView(int64_t now, StopCause cause) const {
  StopView v;
  v.has_committed = hasCommitted();
  v.committed_is_stop = committed_.mode == Mode::kStop;
  v.odometry_speed_mps = odometry_ ? odometry_->velocity.norm() : 0.0;
  // The rule for a failed round does not read it, and runs on every input while recovering.
  if (v.has_committed && cause != StopCause::kNoUsableAnswer) {
    const double elapsed_s = std::max(0.0, (now - committed_.start_utime) * kUs);
    const Trajectory& t = committed_.trajectory;
    v.planned_speed_ahead_mps =
        elapsed_s < t.duration() ? t.tail(elapsed_s).maxSpeed() : t.velocity(t.duration()).norm();
  }
  v.stopped_for_stale_map = stopped_for_stale_map_;
  return v;
}

void Arbiter::evaluate(int64_t now) {
  if (!hasGoal() || !odometry_) return;
  if (round_ && now > round_->deadline_utime) {
    decide(now, true);
    return;
  }
  reportBrakingOnBackupStop(now);
  const bool odometry_stale = odometryStale(now);
  if (!odometry_stale) slowDownIfTooFast(now);
  if (round_ || phase_ == Phase::kReached) return;
  if (odometry_stale) {
    onStaleOdometry(now);
    return;
  }
  if (goalReached((vehiclePosition() - goal_.position).norm(), hasCommitted(),
                  committed_.ends_at_goal, params_)) {
    phase_ = Phase::kReached;
    DecisionOut d;
    d.outcome = Outcome::kReached;
    d.detail = "goal reached";
    pushDecision(d);
    return;
  }
  // A planner needs a map; awareness-driven policies also wait for an awareness of this goal.
  if (mapStale(now)) {
    if (shouldStop(StopCause::kStaleMap, stopView(now, StopCause::kStaleMap), params_)) {
      stopped_for_stale_map_ = true;
      commitStop(now, "LOCAL_MAP is stale: stopping until maps return", Trigger::kNone);
    }
    return;
  }
  if (usesAwareness(params_.policy) && (!awareness_ || awareness_->goal_id != goal_.id)) return;
  const StuckResponse stuck = stuckNow(now);
  if (stuck == StuckResponse::kGiveUp && phase_ != Phase::kUnreachable &&
      phase_ != Phase::kNewGoal) {
    giveUp(now);
  }
  if (phase_ == Phase::kRecovering) {
    stopIfNoTimeLeft(now, false, "it came close", Trigger::kRetry);
  }
  const ReplanView view = replanView(now);
  const Trigger trigger = nextTrigger(view, params_);
  if (trigger == Trigger::kNone) return;
  const bool braking_in_stop =
      committed_.mode == Mode::kStop && odometry_->velocity.norm() > params_.braking_speed_mps;
  const bool is_stuck = stuck != StuckResponse::kNone;
  if (retryThrottled(trigger, braking_in_stop, view.collision_eta_s.has_value(), is_stuck,
                     view.since_last_round_s, params_)) {
    return;
  }
  const std::optional<double> since_back_off =
      last_backoff_utime_ ? std::optional<double>((now - *last_backoff_utime_) * kUs)
                          : std::nullopt;
  // Stuck: the round backs off to recently flown free space, so that the next rounds start clear
  // of the obstacle they keep failing at.
  std::optional<Eigen::Vector3d> back_off;
  if (grid_ && backOffDue(trigger, stuck, since_back_off, params_)) {
    const int64_t start_utime = takeOverUtime(now);
    back_off = progress_.backOffPoint(*grid_, stateAt(start_utime).position,
                                      params_.backoff_min_distance_m,
                                      params_.inflation_m + params_.backoff_clearance_m);
  }
  const std::vector<Mode> modes = back_off ? chain_.modes() : modesFor(trigger, view, params_);
  if (modes.empty()) return;
  if (trigger == Trigger::kRetry) chain_.beginRetry(modes.front());
  startRound(trigger, modes, now, back_off);
}

double Arbiter::stillUnansweredS(int64_t now) const {
  if (!still_since_utime_) return 0.0;
  return std::max(0.0, (now - std::max(*still_since_utime_, last_answer_utime_)) * kUs);
}

StuckResponse Arbiter::stuckNow(int64_t now) const {
  return stuckResponse(progress_.secondsWithoutProgress(now), stillUnansweredS(now), params_);
}

void Arbiter::slowDownIfTooFast(int64_t now) {
  const double limit_mps = budget_.speed_limit_mps;
  if (!hasCommitted() || committed_.mode == Mode::kStop || committed_.backup ||
      limit_mps >= params_.max_vel_mps)
    return;
  // Not over a commit still to be sent; and a round in flight may still commit its answer, which
  // starts in the state of the trajectory it was asked from: the slowdown may only begin after it.
  if (commit_) return;
  const int64_t start = takeOverUtime(now);
  if (round_ && start < round_->start.start_utime) return;
  const Trajectory slow =
      makeSlowdownTrajectory(committed_.trajectory, (start - committed_.start_utime) * kUs,
                             limit_mps, params_.max_acc_mps2, params_.slowdown_tolerance);
  // Slow enough already, too short to slow down on, or the fitted curve meets an obstacle: the
  // usual rules go on.
  if (slow.empty() || (grid_ && firstCollisionTime(*grid_, slow, 0.0, slow.duration()))) return;
  commit(slow, start, committed_.mode, committed_.ends_at_goal);
  ++counters_.slowdowns;
  DecisionOut d;
  d.outcome = Outcome::kCommitted;
  d.committed_mode = committed_.mode;
  d.trajectory_id = commit_->trajectory_id;
  d.local_target = slow.position(slow.duration());
  d.detail = "slowing down: " + budget_.why;  // it names the speed ("speed lowered to X m/s")
  pushDecision(d);
}

void Arbiter::giveUp(int64_t now) {
  phase_ = Phase::kUnreachable;
  ++counters_.unreachable_goals;
  const std::string why =
      "goal " + std::to_string(goal_.id) + " unreachable: no progress toward it for " +
      std::to_string(static_cast<int>(progress_.secondsWithoutProgress(now))) +
      " s; holding, one retry every " +
      std::to_string(static_cast<int>(params_.unreachable_retry_s)) +
      " s (a new goal resumes at once)" +
      (last_failure_notes_.empty() ? "" : "; last failure: " + last_failure_notes_);
  if (shouldStop(StopCause::kUnreachable, stopView(now, StopCause::kUnreachable), params_)) {
    commitStop(now, why, Trigger::kNone);
  }
  DecisionOut d;
  d.outcome = Outcome::kUnreachable;
  d.local_target = goal_.position;
  d.detail = why;
  pushDecision(d);
}

void Arbiter::startRound(Trigger trigger, const std::vector<Mode>& modes, int64_t now,
                         const std::optional<Eigen::Vector3d>& back_off) {
  if (trigger != Trigger::kRetry) chain_.reset();  // a new episode of attempts
  last_round_utime_ = now;
  Round round;
  round.trigger = trigger;
  if (trigger == Trigger::kCollision) round.note = threat_note_;
  threat_note_.clear();
  round.threat_seen_utime = threat_seen_utime_;
  threat_seen_utime_.reset();
  round.start.start_utime = takeOverUtime(now);
  round.deadline_utime = now + static_cast<int64_t>(budget_.answer_deadline_s * 1e6);
  round.start.state = stateAt(round.start.start_utime);
  // A start faster than the speed limit may keep its speed (the planners could not start
  // otherwise); slowDownIfTooFast brings the committed trajectory down to the limit first.
  round.start.max_speed_mps = std::max(budget_.speed_limit_mps, round.start.state.velocity.norm());
  // EAM on a collision re-optimises the rest of the committed trajectory, ending where it ends,
  // unless that end itself is now inside an obstacle (with the planners' margin, which is wider
  // than the arbiter's own check: EAM refuses a target inside it).
  const Trajectory& committed = committed_.trajectory;
  const double start_s = (round.start.start_utime - committed_.start_utime) * kUs;
  const bool end_clear =
      hasCommitted() && grid_ &&
      isClearOf(*grid_, committed.position(committed.duration()), params_.inflation_m);
  const bool use_reference =
      collisionKeepsReference(trigger, end_clear, start_s, committed.duration(), params_);
  Trajectory reference;
  if (back_off) {
    round.target = *back_off;
    round.target_is_goal = false;
    round.backs_off = true;
    last_backoff_utime_ = now;
    ++counters_.back_offs;
    round.note = "stuck for " +
                 std::to_string(static_cast<int>(progress_.secondsWithoutProgress(now))) +
                 " s: backing off to recently flown free space; " + round.note;
  } else if (use_reference) {
    reference = committed.tail(start_s);
    round.target = committed.position(committed.duration());
    round.target_is_goal = committed_.ends_at_goal;
    round.repairs = true;
  } else {
    const LocalTarget lt = chooseLocalTarget(grid_, round.start.state.position, goal_.position,
                                             params_.horizonDistance(), params_.geofence_min_m,
                                             params_.geofence_max_m, params_.inflation_m);
    round.target = lt.position;
    round.target_is_goal = lt.is_goal;
  }
  for (Mode m : modes) {
    PlanRequestOut r;
    r.request_id = next_request_id_++;
    r.mode = m;
    r.trigger = trigger;
    r.start_utime = round.start.start_utime;
    r.start = round.start.state;
    r.deadline_utime = round.deadline_utime;
    r.max_speed_mps = round.start.max_speed_mps;
    r.map_seq = map_seq_;
    r.target = round.target;
    r.goal = goal_.position;
    if (m == Mode::kEam && use_reference && !back_off) r.reference = reference;
    chain_.markAsked(m);
    latency_.onRequest(r.request_id, m, now);
    round.requests.push_back(r);
    requests_.push_back(r);
  }
  last_round_position_ = vehiclePosition();
  collision_eta_s_.reset();
  if (phase_ == Phase::kNewGoal) phase_ = Phase::kTracking;
  round_ = std::move(round);
}

void Arbiter::enterPhase(Phase phase) {
  if (phase_ == Phase::kNewGoal) return;
  // Unreachable until a round commits (or a new goal comes).
  if (phase_ == Phase::kUnreachable && phase != Phase::kTracking) return;
  phase_ = phase;
}

std::optional<double> Arbiter::repairedReplanPointS() const {
  if (!committed_.repaired_replan_utime) return std::nullopt;
  return (*committed_.repaired_replan_utime - committed_.start_utime) * kUs;
}

std::optional<double> Arbiter::keptReplanPointS() const {
  if (!committed_.kept_replan_utime) return std::nullopt;
  return (*committed_.kept_replan_utime - committed_.start_utime) * kUs;
}

int64_t Arbiter::committedReplanUtime() const {
  const double point_s = replanPointS(committed_.trajectory.duration(), committed_.bound_s,
                                      repairedReplanPointS(), params_, keptReplanPointS());
  return committed_.start_utime + static_cast<int64_t>(point_s * 1e6);
}

void Arbiter::commit(const Trajectory& trajectory, int64_t start_utime, Mode mode,
                     bool ends_at_goal, bool repairs) {
  std::optional<int64_t> repaired;
  if (repairs && hasCommitted()) repaired = committedReplanUtime();
  const double straight_m =
      (trajectory.position(trajectory.duration()) - trajectory.position(0.0)).norm();
  const double bound_s = restToRestTime(straight_m, params_.max_vel_mps, params_.max_acc_mps2);
  committed_ = Committed{};
  committed_.trajectory = trajectory;
  committed_.start_utime = start_utime;
  committed_.mode = mode;
  committed_.ends_at_goal = ends_at_goal;
  committed_.repaired_replan_utime = repaired;
  committed_.bound_s = bound_s;
  if (grid_ && isPointBlocked(*grid_, trajectory.position(0.0))) {
    committed_.escape_until_s =
        escapeZoneEnd(trajectory, params_.start_escape_radius_m, params_.escape_step_s);
    committed_.escape_min_distance_m =
        escapeMinDistance(*grid_, trajectory.position(0.0), params_.check_inflation_m);
  }
  CommitOut c;
  c.trajectory_id = next_trajectory_id_++;
  c.start_utime = start_utime;
  c.mode = mode;
  c.trajectory = trajectory;
  commit_ = std::move(c);
  ++counters_.commits;
}

void Arbiter::commitStop(int64_t now, const std::string& why, Trigger trigger,
                         const Trajectory* given) {
  const int64_t start = takeOverUtime(now);
  const Trajectory stop =
      given ? *given
      : hasCommitted()
          ? stopAlongCommitted((start - committed_.start_utime) * kUs)
          : makeStoppingTrajectory(stateAt(start), params_.max_acc_mps2, params_.max_vel_mps);
  commit(stop, start, Mode::kStop, false);
  const std::optional<int64_t> threat_seen = std::exchange(threat_seen_utime_, std::nullopt);
  // Braking is not a plan: keep trying the modes, from the next map on.
  enterPhase(Phase::kRecovering);
  chain_.recordFailure(map_seq_);
  ++counters_.stops;
  DecisionOut d;
  d.trigger = trigger;
  d.outcome = Outcome::kStopping;
  d.committed_mode = Mode::kStop;
  d.trajectory_id = commit_->trajectory_id;
  d.local_target = stop.position(stop.duration());
  d.detail = why;
  d.threat_seen_utime = threat_seen.value_or(0);
  pushDecision(d);
}

void Arbiter::decide(int64_t now, bool by_deadline) {
  Round round = std::move(*round_);
  round_.reset();
  DecisionOut d;
  d.trigger = round.trigger;
  d.local_target = round.target;
  d.request_id = round.requests.empty() ? 0 : round.requests.front().request_id;
  for (const auto& r : round.requests) d.modes_asked |= modeBit(r.mode);
  if (by_deadline) {
    counters_.unanswered += static_cast<int>(round.requests.size() - round.answers.size());
  }

  const ModeAnswer* best = nullptr;
  double best_score = 0.0;
  std::string notes = round.note;
  for (const ModeAnswer& a : round.answers) {
    d.compute_us[modeIndex(a.mode)] = a.compute_us;
    if (!a.ok) {
      notes += std::string(toString(a.mode)) + " failed (" + a.detail + "); ";
      continue;
    }
    std::string why;
    if (!checkAnswer(a.trajectory, a.start_utime, round.start, grid_, params_,
                     budget_.replan_lead_s + params_.known_space_lead_s, &why)) {
      ++counters_.rejected_answers;
      notes += std::string(toString(a.mode)) + " rejected: " + why + "; ";
      continue;
    }
    d.modes_ok |= modeBit(a.mode);
    const double s = answerScore(a.trajectory, goal_.position, params_);
    if (!best || s < best_score) {
      best = &a;
      best_score = s;
    }
  }
  if (best && now > round.start.start_utime) {
    notes += "answer came after its start time; ";
    best = nullptr;
  }
  if (best && odometryStale(now)) {
    ++counters_.not_committed_stale_odom;
    notes += "ODOMETRY is stale: answer not committed; ";
    best = nullptr;
  }
  if (best && hasCommitted()) {
    const double start_s = (round.start.start_utime - committed_.start_utime) * kUs;
    const Trajectory rest = committed_.trajectory.tail(start_s);
    const double committed_score = answerScore(rest, goal_.position, params_);
    if (keepsCommitted(round.trigger, best_score, committed_score, rest.duration(), params_)) {
      committed_.kept_replan_utime =
          committed_.start_utime +
          static_cast<int64_t>(
              replanPointAfterKeepS(start_s, committed_.trajectory.duration(), params_) * 1e6);
      ++counters_.kept_trajectories;
      d.outcome = Outcome::kKept;
      d.committed_mode = committed_.mode;
      d.trajectory_id = next_trajectory_id_ - 1;
      char text[200];
      std::snprintf(text, sizeof text,
                    "%s's answer would reach the goal in %.1f s, the committed %s trajectory in "
                    "%.1f s%s: kept, replanning in %.1f s",
                    toString(best->mode), best_score, toString(committed_.mode), committed_score,
                    params_.score_jerk_weight_s > 0.0 ? " (scores with their jerk energy)" : "",
                    (*committed_.kept_replan_utime - round.start.start_utime) * kUs);
      d.detail = notes + text;
      pushDecision(d);
      return;
    }
  }
  if (best) {
    if (phase_ == Phase::kUnreachable) progress_.restart(now);  // a new chance to progress
    commit(best->trajectory, round.start.start_utime, best->mode, round.target_is_goal,
           round.repairs);
    last_answer_utime_ = now;
    enterPhase(Phase::kTracking);
    chain_.reset();
    d.outcome = Outcome::kCommitted;
    d.committed_mode = best->mode;
    d.trajectory_id = commit_->trajectory_id;
    d.detail = notes + "committed " + toString(best->mode);
    d.threat_seen_utime = round.threat_seen_utime.value_or(0);
    pushDecision(d);
    return;
  }
  if (round.backs_off) {
    d.detail = notes;
    if (retraceOutOfTheSpot(round, d)) return;
  }
  // The danger stays unanswered: the retry, or the stop, answers it.
  if (round.threat_seen_utime &&
      (!threat_seen_utime_ || *round.threat_seen_utime < *threat_seen_utime_)) {
    threat_seen_utime_ = round.threat_seen_utime;
  }
  ++counters_.failures;
  enterPhase(Phase::kRecovering);
  chain_.recordFailure(map_seq_);
  if (by_deadline && round.answers.size() < round.requests.size()) {
    notes += "no answer by the deadline; ";
  }
  d.outcome = Outcome::kFailed;
  d.detail = notes;
  last_failure_notes_ = notes;
  pushDecision(d);
  if (stopIfNoTimeLeft(now, by_deadline, notes, round.trigger)) {
    flyOnWithBackupStop(now, round.trigger);
  } else {
    swerveIfStopMeetsObstacle(now, notes, round.trigger);
  }
}

bool Arbiter::retraceOutOfTheSpot(const Round& round, DecisionOut& d) {
  // A vehicle still braking would first run on towards what it is stuck at: it is retraced
  // from rest, at the next back-off. Nor once the goal is given up: only a mode's answer gives
  // the flight another chance (a way back would be a new one each time, without end).
  const KinematicState& start = round.start.state;
  if (!grid_ || now_ > round.start.start_utime || odometryStale(now_) ||
      start.velocity.norm() > params_.braking_speed_mps || phase_ == Phase::kUnreachable)
    return false;
  const std::vector<Eigen::Vector3d> route =
      progress_.backOffRoute(*grid_, start.position, params_.backoff_min_distance_m,
                             params_.inflation_m + params_.backoff_clearance_m, kRetraceSpacingM);
  const std::optional<Trajectory> way = retraceTrajectory(
      start, route, params_.retrace_speed_mps, params_.max_vel_mps, params_.max_acc_mps2);
  // Off the occupied cells by the airframe's touch distance, or, where the vehicle has been
  // nearer than that (the map's cells are coarser than the trunks), no nearer than it has been
  // (keepsEscapeDistance's tolerance): than its start and the positions it flew through.
  double min_distance_m = escapeMinDistance(*grid_, start.position, stopTouchDistance());
  for (const Eigen::Vector3d& flown : route) {
    min_distance_m = std::min(min_distance_m, occupiedDistance(*grid_, flown, min_distance_m));
  }
  if (!way || !keepsOffOccupied(*grid_, *way, min_distance_m, params_.check_step_s)) return false;
  const Geofence fence = fenceFrom(start.position);
  for (double s = 0.0; s <= way->duration(); s += params_.check_step_s) {
    if (!insideGeofence(fence, way->position(s))) return false;
  }
  commit(*way, round.start.start_utime, Mode::kNone, false);
  last_answer_utime_ = now_;
  committed_.retrace = true;
  committed_.escape_min_distance_m = min_distance_m;
  // Flown to its end before the modes plan again (a halfway replan from inside the spot would
  // lead back into it); a danger on it still asks them at once.
  committed_.kept_replan_utime =
      round.start.start_utime + static_cast<int64_t>(way->duration() * 1e6);
  enterPhase(Phase::kTracking);
  chain_.reset();
  ++counters_.retraces;
  d.outcome = Outcome::kCommitted;
  d.committed_mode = Mode::kNone;
  d.trajectory_id = commit_->trajectory_id;
  d.local_target = route.back();
  char text[160];
  std::snprintf(text, sizeof(text),
                "no mode answered the back-off: flying back the way the vehicle came, %.1f m in "
                "%.1f s",
                way->arcLength(0.0, way->duration()), way->duration());
  d.detail += text;
  pushDecision(d);
  return true;
}

bool Arbiter::stopIfNoTimeLeft(int64_t now, bool by_deadline, const std::string& notes,
                               Trigger trigger) {
  StopView stop = stopView(now, StopCause::kNoUsableAnswer);
  const bool obstacle = collisionAhead(now);
  stop.danger_ahead = obstacle || unmappedAhead(now, params_.stop_decision_margin_s).has_value();
  stop.fallback_exhausted = chain_.exhausted();
  stop.by_deadline = by_deadline;
  if (!stop.danger_ahead || stop.committed_is_stop) return false;
  const bool stuck = stuckNow(now) != StuckResponse::kNone;
  stop.retry_held_back = retryThrottled(Trigger::kRetry, false, false, stuck,
                                        (now - last_round_utime_) * kUs, params_);
  stop.stop_can_wait = stopCanWait(now);
  if (!shouldStop(StopCause::kNoUsableAnswer, stop, params_)) return stop.stop_can_wait;
  commitStop(now,
             std::string("no usable answer and ") +
                 (obstacle ? "danger ahead: " : "unmapped space within stopping reach: ") + notes,
             trigger);
  return false;
}

void Arbiter::swerveIfStopMeetsObstacle(int64_t now, const std::string& notes, Trigger trigger) {
  if (!hasCommitted() || committed_.mode != Mode::kStop || commit_ || round_ ||
      !collisionAhead(now))
    return;
  const int64_t start = takeOverUtime(now);
  const double t0 = (start - committed_.start_utime) * kUs;
  if (t0 >= committed_.trajectory.duration()) return;
  // Braking along the stop under way, or straight, meets the obstacle as the stop does: a stop
  // clear of it is worth committing, and so is one that keeps the airframe off the occupied cells
  // that the stop under way would touch; else the modes go on trying.
  const Trajectory stop = stopAlongCommitted(t0);
  const Geofence fence = fenceFrom(stop.position(0.0));
  std::string how = "swerving round it";
  if (!isClearStop(*grid_, stop, params_.check_inflation_m, &fence, noHiddenFaceBeside())) {
    const double touch_m = stopTouchDistance();
    const Trajectory rest = committed_.trajectory.tail(t0);
    if (minOccupiedDistance(*grid_, rest, touch_m) >= touch_m ||
        minOccupiedDistance(*grid_, stop, touch_m) < touch_m)
      return;
    ++counters_.last_resort_stops;
    how = "no clear stop, taking the one that keeps the airframe off it";
  }
  ++counters_.swerving_stops;
  commitStop(now, "the stop under way meets a newly mapped obstacle: " + how + "; " + notes,
             trigger, &stop);
}

Trajectory Arbiter::backupAlong(const Trajectory& path, double tb) const {
  Trajectory backup = tb > 1e-9 ? path.head(tb) : Trajectory();
  const Trajectory stop =
      makeStoppingTrajectory(path, tb, params_.max_acc_mps2, params_.max_vel_mps);
  for (const Piece& piece : stop.pieces()) backup.append(piece);
  return backup;
}

std::optional<double> Arbiter::latestBackupStopS(const Trajectory& path, double horizon_s,
                                                 double margin_s) const {
  const Geofence fence = fenceFrom(path.position(0.0));
  const StopCondition no_hidden_face = noHiddenFaceBeside();
  auto clear = [&](const Trajectory& t) {
    return isClearStop(*grid_, t, params_.check_inflation_m, &fence, no_hidden_face);
  };
  auto stopFrom = [&](double tb) {
    return makeStoppingTrajectory(path, tb, params_.max_acc_mps2, params_.max_vel_mps);
  };
  // Both bisections keep `lo` at a verified clear point: braking at once is (backupAlong(path, 0)
  // is that stop).
  if (!clear(stopFrom(0.0))) return std::nullopt;
  double lo = 0.0, hi = std::min(horizon_s, path.duration());
  for (int i = 0; i < kBackupSearchSteps; ++i) {
    const double mid = 0.5 * (lo + hi);
    (clear(stopFrom(mid)) ? lo : hi) = mid;
  }
  const double latest = std::max(0.0, lo - margin_s);
  if (clear(backupAlong(path, latest))) return latest;
  lo = 0.0;
  hi = latest;
  for (int i = 0; i < kBackupSearchSteps; ++i) {
    const double mid = 0.5 * (lo + hi);
    (clear(backupAlong(path, mid)) ? lo : hi) = mid;
  }
  return lo;
}

void Arbiter::setBackup(double backup_stop_s) {
  committed_.backup = backupAlong(committed_.trajectory, backup_stop_s);
  committed_.backup_stop_s = backup_stop_s;
  commit_->trajectory = *committed_.backup;
}

void Arbiter::flyOnWithBackupStop(int64_t now, Trigger trigger) {
  if (!hasCommitted() || committed_.mode == Mode::kStop || commit_ || round_ || !grid_) return;
  const int64_t start = takeOverUtime(now);
  const Trajectory& committed = committed_.trajectory;
  const double t0 = (start - committed_.start_utime) * kUs;
  // A backup stop about to begin is not moved: the vehicle brakes on it.
  if (t0 >= committed.duration() || (committed_.backup && t0 >= committed_.backup_stop_s)) return;
  // The path flown on: the committed one from the replan lead, or re-timed slower along it. The
  // re-timed curve meets the danger where the committed one does, only later; it must not meet
  // anything nearer.
  Trajectory path = committed.tail(t0);
  double slowed_to_mps = 0.0;
  if (params_.failed_round_speed_ratio < 1.0) {
    const double speed = committed.velocity(t0).norm();
    const double slower_mps = params_.failed_round_speed_ratio * speed;
    Trajectory slow = makeSlowdownTrajectory(committed, t0, slower_mps, params_.max_acc_mps2);
    bool nearer = false;
    if (!slow.empty()) {
      if (const auto slow_hit = firstCollisionTime(*grid_, slow, 0.0, slow.duration())) {
        const auto hit = committedCollisionTime(t0, committed.duration());
        nearer = !hit || slow.arcLength(0.0, *slow_hit) <
                             committed.arcLength(t0, *hit) - grid_->resolution();
      }
    }
    if (!slow.empty() && !nearer) {
      path = std::move(slow);
      slowed_to_mps = slower_mps;
    }
  }
  // Within the first kBackupHorizonS of the path, before the danger it meets.
  const double search_end = std::min(path.duration(), kBackupHorizonS);
  const auto path_hit = firstCollisionTime(*grid_, path, 0.0, search_end);
  const std::optional<double> backup_s =
      params_.backup_stop ? latestBackupStopS(path, path_hit ? *path_hit : search_end,
                                              params_.stop_decision_margin_s)
                          : std::nullopt;
  if (!backup_s && slowed_to_mps == 0.0) return;  // nothing new: the stop waits as it is
  const bool ends_at_goal = committed_.ends_at_goal;
  commit(path, start, committed_.mode, ends_at_goal);
  if (backup_s) {
    setBackup(*backup_s);
    ++counters_.backup_stops;
  }
  const Trajectory& flown = flownTrajectory();
  if (slowed_to_mps > 0.0) ++counters_.failed_round_slowdowns;
  DecisionOut d;
  d.trigger = trigger;
  d.outcome = Outcome::kCommitted;
  d.committed_mode = committed_.mode;
  d.trajectory_id = commit_->trajectory_id;
  d.local_target = flown.position(flown.duration());
  // The danger's first answer: the vehicle flies on and stops clear of it unless a mode answers
  // in time; the plan that avoids it comes later.
  d.threat_seen_utime = std::exchange(threat_seen_utime_, std::nullopt).value_or(0);
  char text[160];
  if (backup_s) {
    std::snprintf(text, sizeof(text),
                  "every mode failed: flying on%s with a backup stop in %.2f s (%.1f m) unless a "
                  "mode answers: ",
                  slowed_to_mps > 0.0 ? " slower" : "", *backup_s, path.arcLength(0.0, *backup_s));
  } else {
    std::snprintf(text, sizeof(text),
                  "slowing down to %.2f m/s while every mode fails: ", slowed_to_mps);
  }
  d.detail = text + last_failure_notes_;
  pushDecision(d);
}

void Arbiter::reportBrakingOnBackupStop(int64_t now) {
  if (!hasCommitted() || !committed_.backup) return;
  if (now < committed_.start_utime + static_cast<int64_t>(committed_.backup_stop_s * 1e6)) return;
  // From here on it is a stop like any other: no stop on top of it, retries held back.
  committed_.trajectory = *std::exchange(committed_.backup, std::nullopt);
  committed_.mode = Mode::kStop;
  committed_.ends_at_goal = false;
  ++counters_.stops;
  DecisionOut d;
  d.outcome = Outcome::kStopping;
  d.committed_mode = Mode::kStop;
  d.trajectory_id = next_trajectory_id_ - 1;
  d.local_target = committed_.trajectory.position(committed_.trajectory.duration());
  d.detail =
      "no usable answer in time: braking on the backup stop; last failure: " + last_failure_notes_;
  pushDecision(d);
}

void Arbiter::onStaleOdometry(int64_t now) {
  if (stopped_for_stale_odometry_) return;
  stopped_for_stale_odometry_ = true;
  ++counters_.stale_odometry;
  const std::string why = "ODOMETRY is stale (" + std::to_string((now - odometry_utime_) / 1000) +
                          " ms old): no planning until it returns";
  if (shouldStop(StopCause::kStaleOdometry, stopView(now, StopCause::kStaleOdometry), params_)) {
    commitStop(now, why + "; stopping", Trigger::kNone);
    return;
  }
  DecisionOut d;
  d.outcome = Outcome::kRejected;
  d.detail = why;
  pushDecision(d);
}

void Arbiter::pushDecision(DecisionOut d) {
  d.decision_seq = next_decision_seq_++;
  d.utime = now_;
  d.awareness_safe = awareness_ ? awareness_->safe : true;
  d.awareness_reason = awareness_ ? awareness_->reason : 0;
  d.position = vehiclePosition();
  ++counters_.decisions;
  decisions_.push_back(std::move(d));
}

}  // namespace mmh::arbiter
