#include "stack.hpp"

#include <lcm/lcm-cpp.hpp>

#include <chrono>

#include "arbiter_node.hpp"
#include "awareness_node.hpp"
#include "eam_node.hpp"
#include "fpm_node.hpp"
#include "mapping_node.hpp"
#include "mmh/arbiter/arbiter_params.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/goal_t.hpp"
#include "mmh/plan_result_t.hpp"
#include "mmh/trajectory_t.hpp"
#include "sim_node.hpp"
#include "som_node.hpp"

namespace mmh {

namespace {

// Writes every message on the memq bus to an LCM log, stamped with simulated time.
class Recorder {
 public:
  Recorder(const std::string& path, const sim::Simulator* sim) : log_(path, "w"), sim_(sim) {
    if (!log_.good()) throw std::runtime_error("cannot write LCM log " + path);
  }
  void onRaw(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    lcm::LogEvent e;
    e.eventnum = 0;
    e.timestamp = sim_->nowUtime();
    e.channel = channel;
    e.datalen = static_cast<int32_t>(rbuf->data_size);
    e.data = rbuf->data;
    log_.writeEvent(&e);
  }

 private:
  lcm::LogFile log_;
  const sim::Simulator* sim_;
};

}  // namespace

struct Stack::Impl {
  StackOptions options;
  std::unique_ptr<lcm::LCM> lcm;
  std::vector<std::unique_ptr<ServiceContext>> contexts;
  std::unique_ptr<SimNode> sim;
  std::unique_ptr<MappingNode> mapping;
  std::unique_ptr<AwarenessNode> awareness;
  std::unique_ptr<FpmNode> fpm;
  std::unique_ptr<SomNode> som;
  std::unique_ptr<EamNode> eam;
  std::unique_ptr<ArbiterNode> arbiter;
  std::unique_ptr<Recorder> recorder;
  ServiceContext* observer = nullptr;
  FlightRecord record;
  int current_mode = 0;

  ServiceContext& context(const std::string& service) {
    contexts.push_back(std::make_unique<ServiceContext>(*lcm, service, options.prefix));
    return *contexts.back();
  }

  void drain() {
    while (lcm->handleTimeout(0) > 0) {
    }
  }

  // Observer handlers: what the benchmark needs to know about planning.
  void onPlanResult(const plan_result_t& msg) {
    PlanCall c;
    c.mode = msg.mode;
    c.ok = msg.status == plan_result_t::STATUS_OK;
    c.reason = msg.reason;
    c.compute_ms = msg.compute_us * 1e-3;
    c.sim_time_s = (sim->nowUtime() - options.sim.start_utime) * 1e-6;
    record.calls.push_back(c);
    if (msg.mode >= 1 && msg.mode <= 4) ++record.iterations[msg.mode];
  }
  void onTrajectory(const trajectory_t& msg) {
    current_mode = msg.source_mode;
    ++record.commits;
    if (msg.source_mode == plan_request_t::MODE_STOP) ++record.stops;
  }
  void onStatus(const arbiter_status_t& msg) {
    if (msg.outcome == arbiter_status_t::OUTCOME_FAILED) ++record.failed_decisions;
  }
};

Stack::Stack(const StackOptions& options) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.options = options;
  s.lcm = openLcm("memq://");
  const Config& config = options.config;
  // Planners first, simulator last: when the simulator publishes, everyone already listens.
  s.mapping = std::make_unique<MappingNode>(s.context("mmh-mapping"), config);
  s.awareness = std::make_unique<AwarenessNode>(s.context("mmh-awareness"), config);
  s.fpm = std::make_unique<FpmNode>(s.context("mmh-fpm"), config);
  s.som = std::make_unique<SomNode>(s.context("mmh-som"), config);
  s.eam = std::make_unique<EamNode>(s.context("mmh-eam"), config);
  arbiter::ArbiterParams params = arbiter::loadArbiterParams(config);
  if (!options.policy.empty()) params.policy = arbiter::parsePolicy(options.policy);
  s.arbiter = std::make_unique<ArbiterNode>(s.context("mmh-arbiter"), params);
  s.sim = std::make_unique<SimNode>(s.context("mmh-sim"), config, options.sim);
  if (options.map_loss > 0.0) {
    uint64_t seed = options.loss_seed;
    for (auto& ctx : s.contexts) {
      if (ctx->service() != "mmh-sim" && ctx->service() != "mmh-mapping")
        ctx->setIncomingLoss(channels::kLocalMap, options.map_loss, seed++);
    }
  }
  s.observer = &s.context("mmh-stack");
  s.observer->subscribe(channels::kPlanResult, &Impl::onPlanResult, &s);
  s.observer->subscribe(channels::kTrajectory, &Impl::onTrajectory, &s);
  s.observer->subscribe(channels::kArbiterStatus, &Impl::onStatus, &s);
  if (!options.log_path.empty()) {
    s.recorder = std::make_unique<Recorder>(options.log_path, &s.sim->simulator());
    s.lcm->subscribe(".*", &Recorder::onRaw, s.recorder.get());
  }
}

Stack::~Stack() = default;

FlightRecord Stack::fly() {
  Impl& s = *impl_;
  const auto wall_start = std::chrono::steady_clock::now();
  goal_t goal{};
  goal.header.utime = s.sim->nowUtime();
  goal.goal_id = 1;
  fromVec3(s.options.sim.goal, goal.position);
  s.observer->clock().observe(goal.header.utime);
  s.observer->publish(channels::kGoal, goal);
  s.drain();
  const int64_t t0 = s.sim->nowUtime();
  const int64_t limit = t0 + static_cast<int64_t>(s.options.timeout_s * 1e6);
  int64_t next_sample = t0;
  while (true) {
    s.sim->step();
    s.drain();
    const int64_t now = s.sim->nowUtime();
    for (auto& ctx : s.contexts) ctx->maybePublishHeartbeat(now);
    s.drain();
    if (now >= next_sample) {
      next_sample += 100'000;
      const auto& v = s.sim->simulator().vehicle();
      PathSample p;
      p.t = (now - t0) * 1e-6;
      p.position = v.state().position;
      p.speed = v.state().velocity.norm();
      p.mode = s.current_mode;
      s.record.path.push_back(p);
    }
    if (s.sim->finished() || now >= limit) break;
  }
  s.record.metrics = s.sim->metrics();
  s.record.sim_time_s = (s.sim->nowUtime() - t0) * 1e-6;
  s.record.end_reason =
      s.record.metrics.collided ? "collided" : (s.record.metrics.reached ? "reached" : "timeout");
  s.record.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return s.record;
}

}  // namespace mmh
