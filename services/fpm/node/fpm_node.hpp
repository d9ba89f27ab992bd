// The Fast Planning Mode node: answers every PLAN_REQUEST_FPM with one PLAN_RESULT (FPM needs
// no map: it plans without obstacles, the arbiter asks it only where awareness says the way is
// clear).
#pragma once

#include "mmh/common/lcm_runtime.hpp"
#include "mmh/fpm/planner.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/plan_result_t.hpp"

namespace mmh {

// The planner's request for a PLAN_REQUEST_FPM: start state, target, waypoints, speed limit.
fpm::Request fpmRequestOf(const plan_request_t& msg);

class FpmNode {
 public:
  FpmNode(ServiceContext& ctx, const Config& config);

  void onPlanRequest(const plan_request_t& msg);
  const fpm::Planner& planner() const { return planner_; }

  // The answer to one request (also used by tests and tools without LCM).
  static plan_result_t answer(const fpm::Planner& planner, const plan_request_t& msg);

 private:
  ServiceContext& ctx_;
  fpm::Planner planner_;
  LogLimiter fail_log_;
};

}  // namespace mmh
