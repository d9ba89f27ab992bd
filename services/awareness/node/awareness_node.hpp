// The awareness service node: rebuilds the local map from LOCAL_MAP, keeps the latest pose and
// goal, and answers with AWARENESS on every applied map update and every goal change.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "mmh/awareness/awareness_params.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/local_map_counters.hpp"
#include "mmh/goal_t.hpp"
#include "mmh/local_map_t.hpp"
#include "mmh/odometry_t.hpp"

namespace mmh {

class AwarenessNode {
 public:
  AwarenessNode(ServiceContext& ctx, const Config& config);

  void onLocalMap(const local_map_t& msg);
  void onOdometry(const odometry_t& msg);
  void onGoal(const goal_t& msg);

  const awareness::Params& params() const { return params_; }

 private:
  // Publishes AWARENESS for the current map, pose and goal; `why` names the trigger. Without
  // any of the three it only counts the reason (HEARTBEAT) and marks the service degraded.
  void evaluateAndPublish(const char* why);

  ServiceContext& ctx_;
  awareness::Params params_;
  LocalMapReceiver receiver_;
  std::optional<Eigen::Vector3d> position_;
  std::optional<goal_t> goal_;
};

}  // namespace mmh
