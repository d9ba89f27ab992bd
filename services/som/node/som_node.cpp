#include "som_node.hpp"

#include <cstdio>

#include "mmh/common/log.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/common/plan_status_wire.hpp"

namespace mmh {

namespace {

// What the PLAN_RESULT detail says about the second candidate of a fast start (lead_point.hpp).
const char* leadPathNote(const som::PlanOutput& out) {
  if (out.lead_paths_taken > 0) return "; on a path from a point ahead";
  if (out.lead_paths == 0) return "";
  return out.ok() ? "; a path from a point ahead was slower" : "; also tried from a point ahead";
}

}  // namespace

SomNode::SomNode(ServiceContext& ctx, const Config& config)
    : ctx_(ctx),
      receiver_(config.getDouble("map.inflation_m")),
      planner_(som::loadSomParams(config)),
      publish_debug_(config.getBool("som.publish_debug")) {
  ctx_.subscribe(channels::kLocalMap, &SomNode::onLocalMap, this);
  ctx_.subscribe(channels::kPlanRequestSom, &SomNode::onPlanRequest, this);
}

void SomNode::onLocalMap(const local_map_t& msg) {
  if (applyAndCount(receiver_, msg, ctx_) == LocalMapReceiver::Result::kApplied &&
      receiver_.lastWasKeyframe()) {
    planner_.prepare(receiver_.grid());  // cheap unless resized
  }
}

void SomNode::onPlanRequest(const plan_request_t& req) {
  const int64_t t0 = wallTimeUs();
  plan_result_t result{};
  if (req.mode != plan_request_t::MODE_SOM) {
    result.status = plan_result_t::STATUS_FAILED;
    result.reason = plan_result_t::REASON_BAD_INPUT;
    result.detail = "request mode is not SOM";
    answer(req, result, wallTimeUs() - t0);
    return;
  }
  if (!receiver_.hasMap()) {
    result.status = plan_result_t::STATUS_FAILED;
    result.reason = plan_result_t::REASON_NO_MAP;
    result.detail = "no LOCAL_MAP received yet";
    answer(req, result, wallTimeUs() - t0);
    return;
  }
  last_ = planner_.plan(receiver_.grid(), startStateOf(req), toVec3(req.target), req.max_speed_mps);
  const int64_t compute_us = wallTimeUs() - t0;
  const som::PlanTimings& t = last_.timings;
  char split[320];
  std::snprintf(split, sizeof(split),
                "A* %.2f ms, corridor %.2f ms (%d polytopes), optimisation %.2f ms (%d evals), "
                "verification %.2f ms%s%s%s",
                t.astar.wall_us * 1e-3, t.corridor.wall_us * 1e-3,
                static_cast<int>(last_.corridor.polytopes.size()), t.optimize.wall_us * 1e-3,
                last_.optimizer_evaluations, t.verify.wall_us * 1e-3,
                last_.check_margin_retries > 0 ? "; planned again, off the arbiter's margin" : "",
                leadPathNote(last_),
                last_.clearance_taken > 0 ? "; along the path that keeps clear (cheaper)" : "");
  result.status = last_.ok() ? plan_result_t::STATUS_OK : plan_result_t::STATUS_FAILED;
  result.reason = toWireReason(last_.status);
  result.detail =
      last_.ok() ? std::string(split)
                 : std::string(toString(last_.status)) + ": " + last_.detail + " [" + split + "]";
  result.cost_total = last_.cost_total;
  result.cost_control = last_.cost_control;
  result.cost_time = last_.cost_time;
  result.cost_penalty = last_.cost_penalty;
  if (last_.ok()) toMsg(last_.trajectory, result.trajectory);
  // Cumulative split (wall clock) for HEARTBEAT: divide by plans_ok + plans_failed.
  ctx_.increment("astar_us_total", static_cast<int64_t>(t.astar.wall_us));
  ctx_.increment("corridor_us_total", static_cast<int64_t>(t.corridor.wall_us));
  ctx_.increment("optimize_us_total", static_cast<int64_t>(t.optimize.wall_us));
  ctx_.increment("verify_us_total", static_cast<int64_t>(t.verify.wall_us));
  answer(req, result, compute_us);
  if (publish_debug_) {
    plan_debug_t debug =
        toDebugMsg(som::debugOf(last_), req.request_id, plan_request_t::MODE_SOM, last_.ok());
    ctx_.publish(channels::kPlanDebug, debug);
  }
}

void SomNode::answer(const plan_request_t& req, plan_result_t& result, int64_t compute_us) {
  result.header.utime = ctx_.clock().now();
  result.request_id = req.request_id;
  result.mode = plan_request_t::MODE_SOM;
  result.compute_us = compute_us;
  result.map_seq = receiver_.hasMap() ? receiver_.mapSeq() : 0;
  result.narrow = false;
  result.trajectory.trajectory_id = result.status == plan_result_t::STATUS_OK ? req.request_id : 0;
  result.trajectory.start_utime = req.start_utime;
  result.trajectory.source_mode = plan_request_t::MODE_SOM;
  result.trajectory.header.utime = result.header.utime;
  result.trajectory.header.source = ctx_.service();
  if (result.status == plan_result_t::STATUS_OK) {
    ctx_.increment("plans_ok");
  } else {
    ctx_.increment("plans_failed");
    ctx_.increment("failed_reason_" + std::to_string(result.reason));  // as FPM and EAM
    logInfo("request " + std::to_string(req.request_id) + " failed: " + result.detail);
  }
  ctx_.publish(channels::kPlanResult, result);
}

}  // namespace mmh
