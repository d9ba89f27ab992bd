// LCM adapter of the arbiter: feeds GOAL, ODOMETRY, AWARENESS, LOCAL_MAP and PLAN_RESULT into
// mmh::arbiter::Arbiter and publishes its requests, TRAJECTORY and ARBITER_STATUS.
#pragma once

#include "mmh/arbiter/arbiter.hpp"
#include "mmh/awareness_t.hpp"
#include "mmh/common/config.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/local_map_counters.hpp"
#include "mmh/goal_t.hpp"
#include "mmh/local_map_t.hpp"
#include "mmh/odometry_t.hpp"
#include "mmh/plan_result_t.hpp"

namespace mmh {

class ArbiterNode {
 public:
  ArbiterNode(ServiceContext& ctx, const Config& config);
  ArbiterNode(ServiceContext& ctx, const arbiter::ArbiterParams& params);

  const arbiter::Arbiter& arbiter() const { return arbiter_; }
  // Called often in real time (runNode's periodic): when the inputs fell silent long enough for
  // ODOMETRY to be stale on the clock they would have now, the arbiter learns it at once instead
  // of at the next input (the repeated GOAL comes once a second) and stops the vehicle.
  void onIdle(int64_t wall_now_us);

 private:
  void onGoal(const goal_t& msg);
  void onOdometry(const odometry_t& msg);
  void onAwareness(const awareness_t& msg);
  void onLocalMap(const local_map_t& msg);
  void onPlanResult(const plan_result_t& msg);
  void flush();
  // The newest time of the inputs, or of an idle tick that moved the arbiter's clock on.
  int64_t clockNow() const;

  ServiceContext& ctx_;
  arbiter::Arbiter arbiter_;
  LocalMapReceiver map_;
  LogLimiter failed_log_;  // failed decisions (a goal no mode reaches fails at the map rate)
};

}  // namespace mmh
