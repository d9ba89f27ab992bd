#include "awareness_node.hpp"

#include <chrono>

#include "mmh/awareness_t.hpp"
#include "mmh/common/msg_convert.hpp"

namespace mmh {

AwarenessNode::AwarenessNode(ServiceContext& ctx, const Config& config)
    : ctx_(ctx), params_(awareness::loadParams(config)), receiver_(params_.inflation_m) {
  ctx_.subscribe(channels::kLocalMap, &AwarenessNode::onLocalMap, this);
  ctx_.subscribe(channels::kOdometry, &AwarenessNode::onOdometry, this);
  ctx_.subscribe(channels::kGoal, &AwarenessNode::onGoal, this);
  ctx_.setState(heartbeat_t::STATE_DEGRADED, "waiting for LOCAL_MAP, ODOMETRY and GOAL");
}

void AwarenessNode::onLocalMap(const local_map_t& msg) {
  if (applyAndCount(receiver_, msg, ctx_) == LocalMapReceiver::Result::kApplied) {
    evaluateAndPublish("map");
  }
}

void AwarenessNode::onOdometry(const odometry_t& msg) {
  // The pose only feeds the next evaluation: the decision is refreshed with every map update
  // (mapping publishes at sensor rate), not at the odometry rate.
  position_ = toVec3(msg.position);
}

void AwarenessNode::onGoal(const goal_t& msg) {
  const bool changed =
      !goal_ || goal_->goal_id != msg.goal_id || toVec3(goal_->position) != toVec3(msg.position);
  goal_ = msg;
  if (changed) {
    ctx_.increment("goal_changes");
    evaluateAndPublish("goal");
  }
}

void AwarenessNode::evaluateAndPublish(const char* why) {
  if (!receiver_.hasMap() || !position_ || !goal_) {
    std::string missing;
    if (!receiver_.hasMap()) missing += " LOCAL_MAP";
    if (!position_) missing += " ODOMETRY";
    if (!goal_) missing += " GOAL";
    ctx_.increment(!receiver_.hasMap() ? "skipped_no_map"
                   : !position_        ? "skipped_no_pose"
                                       : "skipped_no_goal");
    ctx_.setState(heartbeat_t::STATE_DEGRADED, "waiting for" + missing);
    return;
  }
  ctx_.setState(heartbeat_t::STATE_OK, "");
  const Eigen::Vector3d goal = toVec3(goal_->position);
  const auto t0 = std::chrono::steady_clock::now();
  const AwarenessResult r =
      evaluateAwareness(receiver_.grid(), *position_, goal, params_.algorithm);
  const auto t1 = std::chrono::steady_clock::now();

  awareness_t out{};
  out.safe = r.safe;
  out.reason = static_cast<int8_t>(r.reason);
  out.map_seq = receiver_.mapSeq();
  out.goal_id = goal_->goal_id;
  fromVec3(*position_, out.position);
  fromVec3(goal, out.goal);
  fromVec3(r.ray_end, out.ray_end);
  out.has_blocked_point = r.has_blocked_point;
  fromVec3(r.first_blocked, out.first_blocked);
  out.compute_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(t1 - t0).count();
  ctx_.increment(std::string("published_on_") + why);
  ctx_.increment(
      r.safe ? "result_clear"
             : (r.reason == AwarenessReason::kBlocked ? "result_blocked" : "result_narrow"));
  ctx_.publish(channels::kAwareness, out);
}

}  // namespace mmh
