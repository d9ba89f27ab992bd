// The planner services of one vehicle (mapping, awareness, FPM, SOM, EAM, arbiter) hosted in one
// process on one memq:// LCM, each with its own ServiceContext. mmh-stack adds the simulator,
// mmh-replay feeds recorded inputs; both deliver every message before the next input (lock-step).
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mmh/common/config.hpp"
#include "mmh/common/lcm_runtime.hpp"

namespace mmh {

class MappingNode;
class AwarenessNode;
class FpmNode;
class SomNode;
class EamNode;
class ArbiterNode;

struct PlannerHostOptions {
  Config config;
  std::string prefix;     // channel prefix of the vehicle
  std::string policy;     // empty: arbiter.policy from the config
  double map_loss = 0.0;  // test switch: share of LOCAL_MAP messages the planners lose
  uint64_t loss_seed = 1;
};

class PlannerHost {
 public:
  // Starts the six planner services on `bus`, or on its own memq:// when `bus` is null (throws
  // ConfigError, LcmError). Several hosts with different prefixes may share one bus.
  explicit PlannerHost(const PlannerHostOptions& options, lcm::LCM* bus = nullptr);
  ~PlannerHost();
  PlannerHost(const PlannerHost&) = delete;
  PlannerHost& operator=(const PlannerHost&) = delete;

  lcm::LCM& lcm() { return *bus_; }
  const std::string& prefix() const { return options_.prefix; }
  // A further service on the same LCM and prefix (the simulator, an observer); it subscribes
  // after the planners, so it sees each message after them.
  ServiceContext& addContext(const std::string& service);
  // Delivers every queued message, including those published while delivering.
  void drain();
  // HEARTBEAT of every hosted service that is due on the given (simulated) clock.
  void publishHeartbeats(int64_t now_us);
  // In lock-step the host is the clock: every service's message clock moves on to now_us, also
  // of a service whose inputs are rare (FPM). Otherwise its next input, many simulated seconds
  // later but only a few on the wall clock, looks like a jump far ahead and is refused - more
  // or less often depending on how fast the machine runs the steps.
  void advanceClocks(int64_t now_us);
  // Every service (also those added later) reports OK instead of STARTING from now on.
  void markRunning();

 private:
  PlannerHostOptions options_;
  std::unique_ptr<lcm::LCM> own_lcm_;  // null when the bus is shared
  lcm::LCM* bus_ = nullptr;
  std::vector<std::unique_ptr<ServiceContext>> contexts_;
  std::unique_ptr<MappingNode> mapping_;
  std::unique_ptr<AwarenessNode> awareness_;
  std::unique_ptr<FpmNode> fpm_;
  std::unique_ptr<SomNode> som_;
  std::unique_ptr<EamNode> eam_;
  std::unique_ptr<ArbiterNode> arbiter_;
};

}  // namespace mmh
