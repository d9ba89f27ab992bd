// EamNode: the LCM face of the Emergency Avoidance Mode. Rebuilds the map from LOCAL_MAP and
// answers every PLAN_REQUEST_EAM with one PLAN_RESULT.
#pragma once

#include "mmh/common/config.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/local_map_counters.hpp"
#include "mmh/eam/planner.hpp"
#include "mmh/local_map_t.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/plan_result_t.hpp"

namespace mmh {

// The planner's request for a PLAN_REQUEST_EAM: start state, target, speed limit, and as the
// initial guess the part of the committed trajectory (reference) from the request's start time.
eam::PlanRequest eamRequestOf(const plan_request_t& msg);

class EamNode {
 public:
  EamNode(ServiceContext& ctx, const Config& config);

  void onLocalMap(const local_map_t& msg);
  void onPlanRequest(const plan_request_t& msg);

  const LocalMapReceiver& map() const { return map_; }
  const eam::Planner& planner() const { return planner_; }

 private:
  void publishFailure(const plan_request_t& req, int16_t reason, const std::string& detail,
                      int64_t started_us);

  ServiceContext& ctx_;
  LocalMapReceiver map_;
  eam::Planner planner_;
  bool publish_debug_ = false;  // eam.publish_debug: PLAN_DEBUG after each answer
};

}  // namespace mmh
