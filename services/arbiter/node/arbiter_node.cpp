#include "arbiter_node.hpp"

#include <algorithm>

#include "mmh/arbiter_status_t.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/trajectory_t.hpp"

namespace mmh {
namespace {

const char* requestChannel(arbiter::Mode mode) {
  switch (mode) {
    case arbiter::Mode::kFpm:
      return channels::kPlanRequestFpm;
    case arbiter::Mode::kSom:
      return channels::kPlanRequestSom;
    default:
      return channels::kPlanRequestEam;
  }
}

}  // namespace

ArbiterNode::ArbiterNode(ServiceContext& ctx, const Config& config)
    : ArbiterNode(ctx, arbiter::loadArbiterParams(config)) {}

ArbiterNode::ArbiterNode(ServiceContext& ctx, const arbiter::ArbiterParams& params)
    : ctx_(ctx), arbiter_(params), map_(params.check_inflation_m) {
  ctx_.subscribe(channels::kGoal, &ArbiterNode::onGoal, this);
  ctx_.subscribe(channels::kOdometry, &ArbiterNode::onOdometry, this);
  ctx_.subscribe(channels::kAwareness, &ArbiterNode::onAwareness, this);
  ctx_.subscribe(channels::kLocalMap, &ArbiterNode::onLocalMap, this);
  ctx_.subscribe(channels::kPlanResult, &ArbiterNode::onPlanResult, this);
  ctx_.setState(heartbeat_t::STATE_DEGRADED, "waiting for goal, odometry and map");
}

void ArbiterNode::onGoal(const goal_t& msg) {
  std::string why;
  if (!arbiter_.setGoal(msg.goal_id, toVec3(msg.position), ctx_.clock().now(), &why)) {
    ctx_.reject("rejected_goal", "goal " + std::to_string(msg.goal_id) + " refused: " + why);
  }
  flush();
}

void ArbiterNode::onOdometry(const odometry_t& msg) {
  arbiter_.onOdometry(stateOf(msg), msg.header.utime);
  if (arbiter_.hasGoal() && map_.hasMap() && !arbiter_.odometryStale(clockNow()) &&
      !arbiter_.latencyBudget().degraded) {
    ctx_.setState(heartbeat_t::STATE_OK, "");
  }
  flush();
}

void ArbiterNode::onAwareness(const awareness_t& msg) {
  arbiter_.setAwareness(msg.safe, msg.reason, msg.goal_id, msg.map_seq);
}

void ArbiterNode::onLocalMap(const local_map_t& msg) {
  if (applyAndCount(map_, msg, ctx_) == LocalMapReceiver::Result::kApplied) {
    arbiter_.onMapUpdated(map_.grid(), map_.mapSeq(), map_.mapUtime(), ctx_.clock().now());
    flush();
  }
}

void ArbiterNode::onPlanResult(const plan_result_t& msg) {
  arbiter::ModeAnswer a;
  a.request_id = msg.request_id;
  a.mode = static_cast<arbiter::Mode>(msg.mode);
  a.ok = msg.status == plan_result_t::STATUS_OK;
  a.reason = msg.reason;
  a.detail = msg.detail;
  a.compute_us = msg.compute_us;
  a.start_utime = msg.trajectory.start_utime;
  if (a.ok) a.trajectory = fromMsg(msg.trajectory);
  arbiter_.onAnswer(a, ctx_.clock().now());
  flush();
}

void ArbiterNode::onIdle(int64_t wall_now_us) {
  const int64_t now = ctx_.estimatedNow(wall_now_us);
  // While inputs flow, their own times drive the arbiter (the same decisions as in lock-step).
  if (!arbiter_.hasGoal() || arbiter_.reached() || now <= arbiter_.now() ||
      !arbiter_.odometryStale(now)) {
    return;
  }
  arbiter_.onClock(now);
  flush();
}

int64_t ArbiterNode::clockNow() const {
  return std::max(ctx_.clock().now(), arbiter_.now());
}

void ArbiterNode::flush() {
  const int64_t now = ctx_.clock().now();
  for (const arbiter::PlanRequestOut& r : arbiter_.takeRequests()) {
    plan_request_t msg{};
    msg.header.utime = now;
    msg.request_id = r.request_id;
    msg.mode = static_cast<int8_t>(r.mode);
    msg.reason = static_cast<int8_t>(r.trigger);
    msg.start_utime = r.start_utime;
    setStartState(r.start, msg);
    fromVec3(r.target, msg.target);
    fromVec3(r.goal, msg.goal);
    msg.deadline_utime = r.deadline_utime;
    msg.max_speed_mps = r.max_speed_mps;
    msg.map_seq = r.map_seq;
    setWaypoints({}, msg);
    if (!r.reference.empty()) {
      toMsg(r.reference, msg.reference);
      msg.reference.start_utime = r.start_utime;
      msg.reference.header.utime = now;
    }
    ctx_.publish(requestChannel(r.mode), msg);
  }
  if (auto c = arbiter_.takeCommit()) {
    trajectory_t msg{};
    msg.header.utime = now;
    msg.trajectory_id = c->trajectory_id;
    msg.start_utime = c->start_utime;
    msg.source_mode = static_cast<int8_t>(c->mode);
    toMsg(c->trajectory, msg);
    ctx_.publish(channels::kTrajectory, msg);
  }
  const arbiter::ArbiterCounters& n = arbiter_.counters();
  for (const arbiter::DecisionOut& d : arbiter_.takeDecisions()) {
    arbiter_status_t msg{};
    msg.header.utime = d.utime ? d.utime : now;
    msg.decision_seq = d.decision_seq;
    msg.trigger = static_cast<int8_t>(d.trigger);
    msg.outcome = static_cast<int8_t>(d.outcome);
    msg.awareness_safe = d.awareness_safe;
    msg.awareness_reason = d.awareness_reason;
    msg.modes_asked = static_cast<int8_t>(d.modes_asked);
    msg.modes_answered_ok = static_cast<int8_t>(d.modes_ok);
    msg.committed_mode = static_cast<int8_t>(d.committed_mode);
    msg.request_id = d.request_id;
    msg.committed_trajectory_id = d.trajectory_id;
    msg.compute_us_fpm = d.compute_us[1];
    msg.compute_us_som = d.compute_us[2];
    msg.compute_us_eam = d.compute_us[3];
    msg.iterations_fpm = n.iterations[1];
    msg.iterations_som = n.iterations[2];
    msg.iterations_eam = n.iterations[3];
    msg.failures = n.failures;
    fromVec3(d.position, msg.position);
    fromVec3(d.local_target, msg.local_target);
    msg.detail = d.detail;
    const arbiter::LatencyBudget& budget = arbiter_.latencyBudget();
    msg.replan_lead_s = budget.replan_lead_s;
    msg.answer_deadline_s = budget.answer_deadline_s;
    msg.degraded = budget.degraded;
    msg.degraded_reason = budget.why;
    msg.threat_seen_utime = d.threat_seen_utime;
    ctx_.publish(channels::kArbiterStatus, msg);
    if (d.outcome == arbiter::Outcome::kStopping) logWarn("arbiter: stopping: " + d.detail);
    if (d.outcome == arbiter::Outcome::kUnreachable) logWarn("arbiter: " + d.detail);
    if (d.outcome == arbiter::Outcome::kGoalMoved) logWarn("arbiter: " + d.detail);
    if (d.outcome == arbiter::Outcome::kFailed && failed_log_.shouldLog()) {
      logWarn("arbiter: decision " + std::to_string(d.decision_seq) + " failed: " + d.detail);
    }
  }
  // The library's fault counters, mirrored into HEARTBEAT.
  ctx_.setCounter("odometry_stale", n.stale_odometry);
  ctx_.setCounter("not_committed_odometry_stale", n.not_committed_stale_odom);
  ctx_.setCounter("unanswered_requests", n.unanswered);
  ctx_.setCounter("stops", n.stops);
  ctx_.setCounter("failed_decisions", n.failures);  // e.g. an unreachable goal: every mode fails
  ctx_.setCounter("rejected_answers", n.rejected_answers);
  ctx_.setCounter("unreachable_goals", n.unreachable_goals);
  ctx_.setCounter("back_offs", n.back_offs);
  ctx_.setCounter("moved_goals", n.moved_goals);
  ctx_.setCounter("kept_trajectories", n.kept_trajectories);
  ctx_.setCounter("degraded_periods", n.degraded_periods);
  ctx_.setCounter("slowdowns", n.slowdowns);
  ctx_.setCounter("failed_round_slowdowns", n.failed_round_slowdowns);
  ctx_.setCounter("swerving_stops", n.swerving_stops);
  ctx_.setCounter("last_resort_stops", n.last_resort_stops);
  ctx_.setCounter("backup_stops", n.backup_stops);
  ctx_.setCounter("retraces", n.retraces);
  // Latencies as gauges (ms), so that mmh-top and a log show what the budget sees.
  auto milliseconds = [](double seconds) { return static_cast<int64_t>(seconds * 1e3); };
  ctx_.setCounter("answer_latency_p99_ms",
                  milliseconds(arbiter_.latencyBudget().answer_latency_p99_s));
  ctx_.setCounter("map_age_p99_ms", milliseconds(arbiter_.latencyBudget().map_age_p99_s));
  ctx_.setCounter("answer_deadline_ms", milliseconds(arbiter_.latencyBudget().answer_deadline_s));
  ctx_.setCounter("speed_limit_cmps",
                  static_cast<int64_t>(arbiter_.latencyBudget().speed_limit_mps * 100.0));
  if (arbiter_.odometryStale(clockNow())) {
    ctx_.setState(heartbeat_t::STATE_DEGRADED, "ODOMETRY is stale: not planning");
  } else if (arbiter_.latencyBudget().degraded && arbiter_.hasGoal() && map_.hasMap()) {
    // A steady text (the numbers change with every answer; they are in the counters above and
    // in ARBITER_STATUS.degraded_reason), so that the log says once when it began.
    ctx_.setState(heartbeat_t::STATE_DEGRADED,
                  "latency budget above the configured one (answer_deadline_ms, "
                  "answer_latency_p99_ms, map_age_p99_ms)");
  }
}

}  // namespace mmh
