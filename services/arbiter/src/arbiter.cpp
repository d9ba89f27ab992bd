#include "mmh/arbiter/arbiter.hpp"

#include <algorithm>
#include <cmath>

#include "mmh/arbiter/local_target.hpp"
#include "mmh/arbiter/stopping_trajectory.hpp"
#include "mmh/common/collision_check.hpp"

namespace mmh::arbiter {
namespace {

constexpr double kUs = 1e-6;  // seconds per microsecond
// The planners keep mmh::kEscapeDepthTolerance on their own samples; this check samples in
// time (1 cm of time, up to 3 cm apart at v_max), so it allows a little more between them.
constexpr double kArbiterEscapeDepthTolerance = 0.03;  // m

bool usesAwareness(Policy p) {
  return p == Policy::kMmh || p == Policy::kMmhNoLazy;
}
bool usesLazyRules(Policy p) {
  return p == Policy::kMmh || p == Policy::kMmhNoAwareness;
}

int modeIndex(Mode m) {
  return static_cast<int>(m);
}

}  // namespace

Arbiter::Arbiter(const ArbiterParams& params) : params_(params) {}

bool Arbiter::mapStale(int64_t now) const {
  return map_seq_ == 0 || (now - map_utime_) * kUs > params_.stale_map_s;
}

bool Arbiter::odometryStale(int64_t now) const {
  return have_odometry_ && (now - odometry_utime_) * kUs > params_.stale_odometry_s;
}

bool Arbiter::setGoal(int64_t goal_id, const Eigen::Vector3d& goal, int64_t now, std::string* why) {
  now_ = std::max(now_, now);
  if (goal_ && goal_id == goal_id_ && (goal - *goal_).norm() < 1e-6) {  // repeat
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
  if ((goal.array() < params_.geofence_min_m.array()).any() ||
      (goal.array() > params_.geofence_max_m.array()).any()) {
    return refuse("outside the geofence");
  }
  if (grid_ && grid_->isOccupiedPoint(goal)) return refuse("inside a mapped obstacle");
  goal_ = goal;
  goal_id_ = goal_id;
  goal_changed_ = true;
  reached_ = false;
  last_failed_ = false;
  tried_modes_ = 0;
  evaluate(now_);
  return true;
}

void Arbiter::setAwareness(bool safe, int8_t reason, int64_t goal_id, int64_t /*map_seq*/) {
  have_awareness_ = true;
  awareness_safe_ = safe;
  awareness_reason_ = reason;
  awareness_goal_id_ = goal_id;
}

void Arbiter::onMapUpdated(const VoxelGrid& grid, int64_t map_seq, int64_t map_utime, int64_t now) {
  grid_ = &grid;
  map_seq_ = map_seq;
  map_utime_ = map_utime;
  now_ = std::max(now_, now);
  if (stopped_for_stale_map_ && !mapStale(now_)) stopped_for_stale_map_ = false;
  // Rule (2): a newly mapped obstacle on the rest of the committed trajectory.
  double eta_s = 0.0;
  if (hasCommitted() && !pending_ && !reached_ && collisionThreat(now_, &eta_s)) {
    collision_eta_s_ = collision_detected_ ? std::min(collision_eta_s_, eta_s) : eta_s;
    collision_detected_ = true;
  }
  evaluate(now_);
}

void Arbiter::onOdometry(const KinematicState& state, int64_t now) {
  odometry_ = state;
  have_odometry_ = true;
  odometry_utime_ = std::max(odometry_utime_, now);
  now_ = std::max(now_, now);
  if (stopped_for_stale_odometry_ && !odometryStale(now_)) stopped_for_stale_odometry_ = false;
  evaluate(now_);
}

void Arbiter::onAnswer(const ModeAnswer& answer, int64_t now) {
  now_ = std::max(now_, now);
  if (answer.mode >= Mode::kFpm && answer.mode <= Mode::kEam) {
    ++counters_.iterations[modeIndex(answer.mode)];
  }
  if (!pending_) {
    ++counters_.late_answers;
    return;
  }
  bool known = false;
  for (const auto& r : pending_->requests) {
    known |= (r.request_id == answer.request_id && r.mode == answer.mode);
  }
  bool duplicate = false;
  for (const auto& a : pending_->answers) duplicate |= (a.request_id == answer.request_id);
  if (!known || duplicate) {
    ++counters_.late_answers;
    return;
  }
  pending_->answers.push_back(answer);
  if (pending_->answers.size() == pending_->requests.size()) decide(now_, false);
}

KinematicState Arbiter::stateAt(int64_t utime) const {
  if (hasCommitted()) return committed_.state((utime - committed_start_) * kUs);
  KinematicState hold;
  hold.position = odometry_.position;
  return hold;
}

bool Arbiter::collisionAhead(int64_t now) const {
  if (!grid_ || !hasCommitted()) return false;
  const double t0 = std::max(0.0, (now - committed_start_) * kUs);
  return firstCollisionTime(*grid_, committed_, t0, committed_.duration()).has_value();
}

bool Arbiter::collisionThreat(int64_t now, double* eta_s) const {
  if (!grid_ || !hasCommitted()) return false;
  const double elapsed = std::max(0.0, (now - committed_start_) * kUs);
  const auto hit = firstCollisionTime(*grid_, committed_, elapsed, committed_.duration());
  if (!hit) return false;
  if (eta_s) *eta_s = *hit - elapsed;
  // The halfway replan plans with this map before the vehicle gets there: leave it to it.
  const bool halfway_replan_pending = usesLazyRules(params_.policy) && !committed_ends_at_goal_ &&
                                      elapsed < 0.5 * committed_.duration();
  if (params_.defer_far_collisions && halfway_replan_pending &&
      *hit > 0.5 * committed_.duration() + params_.collision_margin_s) {
    return false;
  }
  return true;
}

Trigger Arbiter::nextTrigger(int64_t now) const {
  if (goal_changed_) return hasCommitted() ? Trigger::kGoalChanged : Trigger::kInitial;
  // After a failed round the fallback chain goes on (a collision seen again on the next map must
  // not restart it with EAM forever, never reaching SOM or the stop).
  const bool can_retry = last_failed_ && !chooseModes(Trigger::kRetry).empty();
  if (collision_detected_ && !can_retry) return Trigger::kCollision;
  if (last_failed_) return can_retry ? Trigger::kRetry : Trigger::kNone;
  if (!hasCommitted()) return Trigger::kInitial;
  const double elapsed = (now - committed_start_) * kUs;
  if (usesLazyRules(params_.policy)) {
    // Rule (1): past the halfway point, unless this trajectory already ends at the goal.
    if (!committed_ends_at_goal_ && elapsed > 0.5 * committed_.duration()) return Trigger::kHalfway;
  } else {
    const double to_goal = (odometry_.position - *goal_).norm();
    if ((odometry_.position - last_plan_position_).norm() >= params_.fixed_replan_distance_m &&
        to_goal > params_.fixed_replan_distance_m) {
      return Trigger::kFixed;
    }
    if (!committed_ends_at_goal_ && elapsed > committed_.duration()) return Trigger::kFixed;
  }
  return Trigger::kNone;
}

std::vector<Mode> Arbiter::chooseModes(Trigger trigger) const {
  const Policy p = params_.policy;
  if (trigger == Trigger::kRetry) {
    // Fallback chain: the next mode not yet asked since the last commit; once all were asked,
    // only a new map can change the answer, so the chain starts again only then.
    std::vector<Mode> chain{Mode::kSom, Mode::kEam};
    if (p == Policy::kEgo) chain = {Mode::kEam};
    if (p == Policy::kSom) chain = {Mode::kSom};
    for (Mode m : chain) {
      if (!(tried_modes_ & modeBit(m))) return {m};
    }
    if (map_seq_ != map_seq_at_failure_) return {chain.front()};
    return {};
  }
  if (p == Policy::kEgo) return {Mode::kEam};
  if (p == Policy::kSom) return {Mode::kSom};
  const bool emergency = collision_eta_s_ <= params_.emergency_horizon_s;
  if (trigger == Trigger::kCollision && (emergency || !usesAwareness(p))) {
    if (params_.parallel_modes != ParallelModes::kNone) return {Mode::kEam, Mode::kSom};
    return {Mode::kEam};
  }
  const bool safe = usesAwareness(p) ? awareness_safe_ : false;
  if (safe) return {Mode::kFpm};
  if (params_.parallel_modes == ParallelModes::kAlways) return {Mode::kSom, Mode::kEam};
  return {Mode::kSom};
}

void Arbiter::evaluate(int64_t now) {
  if (!goal_ || !have_odometry_) return;
  if (pending_) {
    if (now > pending_->deadline_utime) decide(now, true);
    return;
  }
  if (reached_) return;
  if (odometryStale(now)) {
    onStaleOdometry(now);
    return;
  }
  if ((odometry_.position - *goal_).norm() <= params_.goal_tolerance_m &&
      (!hasCommitted() || committed_ends_at_goal_)) {
    reached_ = true;
    DecisionOut d;
    d.outcome = Outcome::kReached;
    d.detail = "goal reached";
    pushDecision(d);
    return;
  }
  // A planner needs a map; awareness-driven policies also wait for an awareness of this goal.
  if (mapStale(now)) {
    if (hasCommitted() && !stopped_for_stale_map_ && odometry_.velocity.norm() > 0.05) {
      stopped_for_stale_map_ = true;
      commitStop(now, "LOCAL_MAP is stale: stopping until maps return", Trigger::kNone);
    }
    return;
  }
  if (usesAwareness(params_.policy) && (!have_awareness_ || awareness_goal_id_ != goal_id_)) {
    return;
  }
  const Trigger trigger = nextTrigger(now);
  if (trigger == Trigger::kNone) return;
  const bool braking = committed_mode_ == Mode::kStop && odometry_.velocity.norm() > 0.1;
  // (A collision on the stop itself is not throttled: only an evasive plan can help then.)
  if (braking && trigger == Trigger::kRetry &&
      (now - last_round_utime_) * kUs < params_.stop_retry_period_s) {
    return;
  }
  const std::vector<Mode> modes = chooseModes(trigger);
  if (modes.empty()) return;
  if (trigger == Trigger::kRetry && (tried_modes_ & modeBit(modes.front()))) {
    tried_modes_ = 0;  // a new map: the chain starts again
  }
  startPlanning(trigger, modes, now);
}

void Arbiter::startPlanning(Trigger trigger, const std::vector<Mode>& modes, int64_t now) {
  if (trigger != Trigger::kRetry) tried_modes_ = 0;  // a new episode of attempts
  last_round_utime_ = now;
  Pending p;
  p.trigger = trigger;
  p.start_utime = now + static_cast<int64_t>(params_.replan_lead_s * 1e6);
  p.deadline_utime = now + static_cast<int64_t>(params_.answer_deadline_s * 1e6);
  p.start = stateAt(p.start_utime);
  Trajectory reference;
  // EAM on a collision re-optimises the rest of the committed trajectory, ending where it ends,
  // unless that end itself is now inside an obstacle (with the planners' margin, which is wider
  // than the arbiter's own check: EAM refuses a target inside it).
  const bool use_reference =
      trigger == Trigger::kCollision && hasCommitted() && grid_ &&
      isClearOf(*grid_, committed_.position(committed_.duration()), params_.inflation_m) &&
      (p.start_utime - committed_start_) * kUs < committed_.duration() - 0.2;
  if (use_reference) {
    reference = committed_.tail((p.start_utime - committed_start_) * kUs);
    p.target = committed_.position(committed_.duration());
    p.target_is_goal = committed_ends_at_goal_;
  } else {
    const LocalTarget lt =
        chooseLocalTarget(grid_, p.start.position, *goal_, params_.horizonDistance(),
                          params_.geofence_min_m, params_.geofence_max_m, params_.inflation_m);
    p.target = lt.position;
    p.target_is_goal = lt.is_goal;
  }
  for (Mode m : modes) {
    PlanRequestOut r;
    r.request_id = next_request_id_++;
    r.mode = m;
    r.trigger = trigger;
    r.start_utime = p.start_utime;
    r.start = p.start;
    r.deadline_utime = p.deadline_utime;
    r.map_seq = map_seq_;
    r.target = p.target;
    r.goal = *goal_;
    if (m == Mode::kEam && use_reference) r.reference = reference;
    tried_modes_ |= modeBit(m);
    p.requests.push_back(r);
    requests_.push_back(r);
  }
  last_plan_position_ = odometry_.position;
  collision_detected_ = false;
  goal_changed_ = false;
  pending_ = std::move(p);
}

bool Arbiter::verifyAnswer(const ModeAnswer& a, std::string* why) const {
  auto fail = [&](const std::string& text) {
    if (why) *why = text;
    return false;
  };
  const Trajectory& t = a.trajectory;
  if (t.empty() || !t.isFinite()) return fail("empty or non-finite trajectory");
  if (t.duration() > params_.max_answer_duration_s)
    return fail("longer than max_answer_duration_s");
  if (a.start_utime != pending_->start_utime) return fail("wrong start time");
  const KinematicState s0 = t.state(0.0);
  // Continuity: the new trajectory must take over the committed one without a jump.
  if ((s0.position - pending_->start.position).norm() > 1e-3 ||
      (s0.velocity - pending_->start.velocity).norm() > 1e-2 ||
      (s0.acceleration - pending_->start.acceleration).norm() > 5e-2) {
    return fail("does not start at the requested state");
  }
  const double tol = 1.0 + params_.answer_speed_tolerance;
  const double start_speed = pending_->start.velocity.norm();
  if (t.maxSpeed() > std::max(params_.max_vel_mps, start_speed) * tol) return fail("too fast");
  if (t.maxAcceleration() > params_.max_acc_mps2 * tol) {
    // A braking start may exceed a_max briefly only if it already did.
    if (t.maxAcceleration() >
        std::max(params_.max_acc_mps2, pending_->start.acceleration.norm()) * tol)
      return fail("accelerates too hard");
  }
  for (double time = 0.0; time <= t.duration(); time += 0.05) {
    const Eigen::Vector3d p = t.position(time);
    if ((p.array() < params_.geofence_min_m.array() - 0.05).any() ||
        (p.array() > params_.geofence_max_m.array() + 0.05).any()) {
      return fail("leaves the geofence");
    }
  }
  double clear_from = 0.0;
  if (grid_ && isPointBlocked(*grid_, s0.position)) {
    // A start inside the margin (e.g. stopped next to a newly mapped obstacle) may leave it, as
    // the planners allow: through no occupied voxel, out of the margin near the start.
    if (firstCollisionTime(*grid_, t, 0.0, t.duration(), CollisionLayer::kOccupied)) {
      return fail("enters an obstacle");
    }
    // Outwards only: never nearer to the occupied cells than the start (or than the check
    // margin), or a vehicle next to an obstacle is re-planned along it until it touches it.
    const double min_distance = escapeMinDistance(*grid_, s0.position, params_.check_inflation_m);
    while (clear_from < t.duration() && isPointBlocked(*grid_, t.position(clear_from))) {
      if (!keepsEscapeDistance(*grid_, t.position(clear_from), min_distance,
                               kArbiterEscapeDepthTolerance)) {
        return fail("goes deeper into the obstacle margin it starts in");
      }
      clear_from += 0.01;
    }
    if ((t.position(clear_from) - s0.position).norm() > params_.start_escape_radius_m) {
      return fail("does not leave the obstacle margin near its start");
    }
  }
  if (grid_ && firstCollisionTime(*grid_, t, clear_from, t.duration()).has_value()) {
    return fail("collides with the arbiter's map");
  }
  return true;
}

double Arbiter::score(const Trajectory& t) const {
  // Estimated time to the goal: this trajectory, then the straight rest at full speed.
  return t.duration() + (*goal_ - t.position(t.duration())).norm() / params_.max_vel_mps;
}

void Arbiter::commit(const Trajectory& trajectory, int64_t start_utime, Mode mode,
                     bool ends_at_goal) {
  committed_ = trajectory;
  committed_start_ = start_utime;
  committed_mode_ = mode;
  committed_ends_at_goal_ = ends_at_goal;
  CommitOut c;
  c.trajectory_id = next_trajectory_id_++;
  c.start_utime = start_utime;
  c.mode = mode;
  c.trajectory = trajectory;
  commit_ = std::move(c);
  ++counters_.commits;
}

void Arbiter::commitStop(int64_t now, const std::string& why, Trigger trigger) {
  const int64_t start = now + static_cast<int64_t>(params_.replan_lead_s * 1e6);
  const Trajectory stop =
      hasCommitted()
          ? chooseStoppingTrajectory(grid_, committed_, (start - committed_start_) * kUs,
                                     params_.max_acc_mps2, params_.max_vel_mps,
                                     params_.check_inflation_m)
          : makeStoppingTrajectory(stateAt(start), params_.max_acc_mps2, params_.max_vel_mps);
  commit(stop, start, Mode::kStop, false);
  // Braking is not a plan: keep trying the modes, from the next map on.
  last_failed_ = true;
  map_seq_at_failure_ = map_seq_;
  ++counters_.stops;
  DecisionOut d;
  d.trigger = trigger;
  d.outcome = Outcome::kStopping;
  d.committed_mode = Mode::kStop;
  d.trajectory_id = commit_->trajectory_id;
  d.local_target = stop.position(stop.duration());
  d.detail = why;
  pushDecision(d);
}

void Arbiter::decide(int64_t now, bool by_deadline) {
  Pending p = std::move(*pending_);
  pending_.reset();
  DecisionOut d;
  d.trigger = p.trigger;
  d.local_target = p.target;
  d.request_id = p.requests.empty() ? 0 : p.requests.front().request_id;
  for (const auto& r : p.requests) d.modes_asked |= modeBit(r.mode);
  if (by_deadline) counters_.unanswered += static_cast<int>(p.requests.size() - p.answers.size());

  const ModeAnswer* best = nullptr;
  double best_score = 0.0;
  std::string notes;
  for (const ModeAnswer& a : p.answers) {
    d.compute_us[modeIndex(a.mode)] = a.compute_us;
    if (!a.ok) {
      notes += std::string(toString(a.mode)) + " failed (" + a.detail + "); ";
      continue;
    }
    std::string why;
    if (!verifyAnswer(a, &why)) {
      ++counters_.rejected_answers;
      notes += std::string(toString(a.mode)) + " rejected: " + why + "; ";
      continue;
    }
    d.modes_ok |= modeBit(a.mode);
    const double s = score(a.trajectory);
    if (!best || s < best_score) {
      best = &a;
      best_score = s;
    }
  }
  if (best && now > p.start_utime) {
    notes += "answer came after its start time; ";
    best = nullptr;
  }
  if (best && odometryStale(now)) {
    ++counters_.not_committed_stale_odom;
    notes += "ODOMETRY is stale: answer not committed; ";
    best = nullptr;
  }
  if (best) {
    commit(best->trajectory, p.start_utime, best->mode, p.target_is_goal);
    last_failed_ = false;
    tried_modes_ = 0;
    d.outcome = Outcome::kCommitted;
    d.committed_mode = best->mode;
    d.trajectory_id = commit_->trajectory_id;
    d.detail = notes + "committed " + toString(best->mode);
    pushDecision(d);
    return;
  }
  ++counters_.failures;
  last_failed_ = true;
  map_seq_at_failure_ = map_seq_;
  if (by_deadline && p.answers.size() < p.requests.size()) notes += "no answer by the deadline; ";
  d.outcome = Outcome::kFailed;
  d.detail = notes;
  // Danger ahead and nothing left to try: brake now rather than fly into it.
  const bool danger = collisionAhead(now);
  const bool out_of_modes = chooseModes(Trigger::kRetry).empty();
  pushDecision(d);
  // A stop already under way brakes as hard as a new one would: recommitting it only resets it.
  const bool braking = committed_mode_ == Mode::kStop;
  if (danger && !braking && (out_of_modes || by_deadline)) {
    commitStop(now, "no usable answer and danger ahead: " + notes, p.trigger);
  }
}

void Arbiter::onStaleOdometry(int64_t now) {
  if (stopped_for_stale_odometry_) return;
  stopped_for_stale_odometry_ = true;
  ++counters_.stale_odometry;
  const std::string why = "ODOMETRY is stale (" + std::to_string((now - odometry_utime_) / 1000) +
                          " ms old): no planning until it returns";
  // The stop continues the committed trajectory, not the stale odometry.
  if (hasCommitted() && committed_mode_ != Mode::kStop && stateAt(now).velocity.norm() > 0.05) {
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
  d.awareness_safe = awareness_safe_;
  d.awareness_reason = awareness_reason_;
  d.position = odometry_.position;
  ++counters_.decisions;
  decisions_.push_back(std::move(d));
}

}  // namespace mmh::arbiter
