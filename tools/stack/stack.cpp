#include "stack.hpp"

#include <lcm/lcm-cpp.hpp>

#include <chrono>

#include "mmh/arbiter_status_t.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/goal_t.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/plan_result_t.hpp"
#include "mmh/trajectory_t.hpp"
#include "planner_host.hpp"
#include "sim_node.hpp"

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
  std::unique_ptr<PlannerHost> host;
  std::unique_ptr<SimNode> sim;
  std::unique_ptr<Recorder> recorder;
  ServiceContext* observer = nullptr;
  FlightRecord record;
  int current_mode = 0;

  void drain() { host->drain(); }

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
  PlannerHostOptions host;
  host.config = options.config;
  host.prefix = options.prefix;
  host.policy = options.policy;
  host.map_loss = options.map_loss;
  host.loss_seed = options.loss_seed;
  // Planners first, simulator last: when the simulator publishes, everyone already listens.
  s.host = std::make_unique<PlannerHost>(host);
  s.sim = std::make_unique<SimNode>(s.host->addContext("mmh-sim"), options.config, options.sim);
  s.observer = &s.host->addContext("mmh-stack");
  s.observer->subscribe(channels::kPlanResult, &Impl::onPlanResult, &s);
  s.observer->subscribe(channels::kTrajectory, &Impl::onTrajectory, &s);
  s.observer->subscribe(channels::kArbiterStatus, &Impl::onStatus, &s);
  if (!options.log_path.empty()) {
    s.recorder = std::make_unique<Recorder>(options.log_path, &s.sim->simulator());
    s.host->lcm().subscribe(".*", &Recorder::onRaw, s.recorder.get());
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
    s.host->publishHeartbeats(now);
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
