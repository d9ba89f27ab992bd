#include "planner_host.hpp"

#include "arbiter_node.hpp"
#include "awareness_node.hpp"
#include "eam_node.hpp"
#include "fpm_node.hpp"
#include "mapping_node.hpp"
#include "mmh/arbiter/arbiter_params.hpp"
#include "som_node.hpp"

namespace mmh {

PlannerHost::PlannerHost(const PlannerHostOptions& options, lcm::LCM* bus) : options_(options) {
  if (bus == nullptr) {
    own_lcm_ = openLcm("memq://");
    bus = own_lcm_.get();
  }
  bus_ = bus;
  const Config& config = options.config;
  mapping_ = std::make_unique<MappingNode>(addContext("mmh-mapping"), config);
  awareness_ = std::make_unique<AwarenessNode>(addContext("mmh-awareness"), config);
  fpm_ = std::make_unique<FpmNode>(addContext("mmh-fpm"), config);
  som_ = std::make_unique<SomNode>(addContext("mmh-som"), config);
  eam_ = std::make_unique<EamNode>(addContext("mmh-eam"), config);
  arbiter::ArbiterParams params = arbiter::loadArbiterParams(config);
  if (!options.policy.empty()) params.policy = arbiter::parsePolicy(options.policy);
  arbiter_ = std::make_unique<ArbiterNode>(addContext("mmh-arbiter"), params);
  if (options.map_loss > 0.0) {
    uint64_t seed = options.loss_seed;
    for (auto& ctx : contexts_) {
      if (ctx->service() != "mmh-mapping")
        ctx->setIncomingLoss(channels::kLocalMap, options.map_loss, seed++);
    }
  }
}

PlannerHost::~PlannerHost() = default;

ServiceContext& PlannerHost::addContext(const std::string& service) {
  contexts_.push_back(std::make_unique<ServiceContext>(*bus_, service, options_.prefix));
  return *contexts_.back();
}

void PlannerHost::drain() {
  while (bus_->handleTimeout(0) > 0) {
  }
}

void PlannerHost::markRunning() {
  for (auto& ctx : contexts_) ctx->markRunning();
}

void PlannerHost::advanceClocks(int64_t now_us) {
  for (auto& ctx : contexts_) ctx->clock().observe(now_us);
}

void PlannerHost::publishHeartbeats(int64_t now_us) {
  for (auto& ctx : contexts_) ctx->maybePublishHeartbeat(now_us, now_us);
}

}  // namespace mmh
