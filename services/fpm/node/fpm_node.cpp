#include "fpm_node.hpp"

#include <chrono>

#include "mmh/common/msg_convert.hpp"
#include "mmh/common/plan_status_wire.hpp"

namespace mmh {

fpm::Request fpmRequestOf(const plan_request_t& msg) {
  fpm::Request request;
  request.start = startStateOf(msg);
  request.target = toVec3(msg.target);
  request.waypoints = getWaypoints(msg);
  request.max_speed_mps = msg.max_speed_mps;
  return request;
}

FpmNode::FpmNode(ServiceContext& ctx, const Config& config)
    : ctx_(ctx), planner_(fpm::loadParams(config)) {
  ctx_.subscribe(channels::kPlanRequestFpm, &FpmNode::onPlanRequest, this);
}

plan_result_t FpmNode::answer(const fpm::Planner& planner, const plan_request_t& msg) {
  plan_result_t out{};
  out.request_id = msg.request_id;
  out.mode = plan_request_t::MODE_FPM;
  out.map_seq = msg.map_seq;  // FPM uses no map: echo the one the request was made on
  out.narrow = false;
  out.trajectory.source_mode = plan_request_t::MODE_FPM;
  out.trajectory.start_utime = msg.start_utime;
  const auto t0 = std::chrono::steady_clock::now();
  fpm::Result r;
  if (msg.mode != plan_request_t::MODE_FPM) {
    r.status = PlanStatus::kBadInput;
    r.detail = "request for mode " + std::to_string(msg.mode) + " on the FPM channel";
  } else {
    r = planner.plan(fpmRequestOf(msg));
  }
  const auto t1 = std::chrono::steady_clock::now();
  out.compute_us = std::chrono::duration_cast<std::chrono::microseconds>(t1 - t0).count();
  out.status = r.ok ? plan_result_t::STATUS_OK : plan_result_t::STATUS_FAILED;
  out.reason = toWireReason(r.status);
  out.detail = r.detail;
  out.cost_control = r.cost.control;
  out.cost_time = r.cost.time;
  out.cost_penalty = r.cost.penalty;
  out.cost_total = r.cost.total();
  if (r.ok) {
    toMsg(r.trajectory, out.trajectory);
    out.trajectory.trajectory_id = msg.request_id;
  } else {
    out.trajectory.num_pieces = 0;
    out.trajectory.pieces.clear();
  }
  return out;
}

void FpmNode::onPlanRequest(const plan_request_t& msg) {
  ctx_.increment("requests");
  plan_result_t out = answer(planner_, msg);
  out.trajectory.header.utime = ctx_.clock().now();
  out.trajectory.header.source = ctx_.service();
  if (out.status == plan_result_t::STATUS_OK) {
    ctx_.increment("planned_ok");
  } else {
    ctx_.increment("failed_reason_" + std::to_string(out.reason));
    if (fail_log_.shouldLog())
      logWarn("mmh-fpm: request " + std::to_string(msg.request_id) + " failed (reason " +
              std::to_string(out.reason) + "): " + out.detail);
  }
  ctx_.publish(channels::kPlanResult, out);
}

}  // namespace mmh
