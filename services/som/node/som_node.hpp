// SomNode: the Standard Optimization Mode as an LCM service. Keeps the local map from LOCAL_MAP
// and answers every PLAN_REQUEST_SOM with one PLAN_RESULT (verified trajectory or a reason).
#pragma once

#include <memory>

#include "mmh/common/config.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/local_map_counters.hpp"
#include "mmh/local_map_t.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/plan_result_t.hpp"
#include "mmh/som/planner.hpp"

namespace mmh {

class SomNode {
 public:
  SomNode(ServiceContext& ctx, const Config& config);

  void onLocalMap(const local_map_t& msg);
  void onPlanRequest(const plan_request_t& msg);

  // Result of the last request (for tests and mmh-stack).
  const som::PlanOutput& lastOutput() const { return last_; }
  const som::SomParams& params() const { return planner_.params(); }

 private:
  void answer(const plan_request_t& req, plan_result_t& result, int64_t compute_us);

  ServiceContext& ctx_;
  LocalMapReceiver receiver_;
  som::Planner planner_;
  som::PlanOutput last_;
  bool publish_debug_ = false;  // som.publish_debug: PLAN_DEBUG after each answer
};

}  // namespace mmh
