#include "eam_node.hpp"

#include "mmh/common/msg_convert.hpp"
#include "mmh/common/plan_status_wire.hpp"

namespace mmh {

eam::PlanRequest eamRequestOf(const plan_request_t& msg) {
  eam::PlanRequest request;
  request.start = startStateOf(msg);
  request.target = toVec3(msg.target);
  request.max_speed_mps = msg.max_speed_mps;
  // The reference is the committed trajectory; only its part from start_utime on is the guess.
  if (msg.reference.num_pieces > 0) {
    const Trajectory committed = fromMsg(msg.reference);
    const double offset_s = 1e-6 * static_cast<double>(msg.start_utime - msg.reference.start_utime);
    if (offset_s <= 0.0)
      request.reference = committed;
    else if (offset_s < committed.duration() - 1e-6)
      request.reference = committed.tail(offset_s);
  }
  return request;
}

EamNode::EamNode(ServiceContext& ctx, const Config& config)
    : ctx_(ctx),
      map_(config.getDouble("map.inflation_m")),
      planner_(eam::loadEamParams(config)),
      publish_debug_(config.getBool("eam.publish_debug")) {
  ctx_.subscribe(channels::kLocalMap, &EamNode::onLocalMap, this);
  ctx_.subscribe(channels::kPlanRequestEam, &EamNode::onPlanRequest, this);
}

void EamNode::onLocalMap(const local_map_t& msg) {
  if (applyAndCount(map_, msg, ctx_) == LocalMapReceiver::Result::kApplied &&
      map_.lastWasKeyframe()) {
    planner_.prepare(map_.grid());  // cheap unless the size changed
  }
}

void EamNode::publishFailure(const plan_request_t& req, int16_t reason, const std::string& detail,
                             int64_t started_us) {
  plan_result_t out{};
  out.request_id = req.request_id;
  out.mode = plan_request_t::MODE_EAM;
  out.status = plan_result_t::STATUS_FAILED;
  out.reason = reason;
  out.detail = detail;
  out.compute_us = wallTimeUs() - started_us;
  out.map_seq = map_.hasMap() ? map_.mapSeq() : 0;
  out.trajectory.start_utime = req.start_utime;
  out.trajectory.source_mode = plan_request_t::MODE_EAM;
  ctx_.increment("plans_failed");
  ctx_.publish(channels::kPlanResult, out);
}

void EamNode::onPlanRequest(const plan_request_t& req) {
  const int64_t started = wallTimeUs();
  if (req.mode != plan_request_t::MODE_EAM) {
    publishFailure(req, plan_result_t::REASON_BAD_INPUT,
                   "request on PLAN_REQUEST_EAM for mode " + std::to_string(req.mode), started);
    return;
  }
  if (!map_.hasMap()) {
    publishFailure(req, plan_result_t::REASON_NO_MAP, "no LOCAL_MAP received yet", started);
    return;
  }
  const eam::PlanResult result = planner_.plan(map_.grid(), eamRequestOf(req));
  plan_result_t out{};
  out.request_id = req.request_id;
  out.mode = plan_request_t::MODE_EAM;
  out.status = result.ok ? plan_result_t::STATUS_OK : plan_result_t::STATUS_FAILED;
  out.reason = toWireReason(result.reason);
  out.detail = result.ok ? "" : std::string(toString(result.reason)) + ": " + result.detail;
  out.map_seq = map_.mapSeq();
  out.narrow = result.narrow;
  // Cost breakdown: control = exact jerk energy of the answer; no time term in EAM; penalty =
  // the weighted collision and feasibility terms left at the optimum.
  out.cost_total = result.terms.total;
  out.cost_control = result.jerk_energy;
  out.cost_time = 0.0;
  out.cost_penalty = result.weights.collision * result.terms.collision +
                     result.weights.feasibility * result.terms.feasibility;
  out.trajectory.start_utime = req.start_utime;
  out.trajectory.source_mode = plan_request_t::MODE_EAM;
  if (result.ok) {
    out.trajectory.trajectory_id = req.request_id;
    toMsg(result.trajectory, out.trajectory);
    ctx_.increment("plans_ok");
  } else {
    ctx_.increment("plans_failed");
    ctx_.increment("failed_reason_" + std::to_string(out.reason));
  }
  if (result.narrow) ctx_.increment("narrow_weights");
  logDebug("request " + std::to_string(req.request_id) + ": " + (result.ok ? "ok" : out.detail) +
           ", duration " + std::to_string(result.stats.initial_duration_s) + " -> " +
           std::to_string(result.trajectory.duration()) + " s, rounds " +
           std::to_string(result.stats.rounds) + ", refines " +
           std::to_string(result.stats.refines) + ", restarts " +
           std::to_string(result.stats.restarts) + ", max acc " +
           std::to_string(result.stats.max_acc));
  out.compute_us = wallTimeUs() - started;
  ctx_.publish(channels::kPlanResult, out);
  if (publish_debug_) {
    plan_debug_t debug =
        toDebugMsg(eam::debugOf(result), req.request_id, plan_request_t::MODE_EAM, result.ok);
    ctx_.publish(channels::kPlanDebug, debug);
  }
}

}  // namespace mmh
