#include "stack.hpp"

#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <chrono>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "mmh/arbiter_status_t.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/goal_t.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/plan_result_t.hpp"
#include "mmh/trajectory_t.hpp"
#include "planner_host.hpp"
#include "setpoint_node.hpp"
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

std::string fixed(double v, int digits) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(digits);
  out << v;
  return out.str();
}

}  // namespace

std::string failureReason(const FailureEvidence& e) {
  if (e.collided) {
    const Eigen::Vector3d& p = e.collision_position;
    return "collided at [" + fixed(p.x(), 2) + ", " + fixed(p.y(), 2) + ", " + fixed(p.z(), 2) +
           "] after " + fixed(e.collision_time_s, 2) + " s";
  }
  if (e.reached) return "";
  if (!e.rejected_detail.empty()) return "refused goal: " + e.rejected_detail;
  if (!e.unreachable_detail.empty()) return "unreachable: " + e.unreachable_detail;
  const std::string left = fixed(e.distance_to_goal_m, 2) + " m from the goal";
  if (e.longest_no_progress_s >= e.stuck_after_s) {
    return "stuck: no progress toward the goal for " + fixed(e.longest_no_progress_s, 1) +
           " s from " + fixed(e.longest_no_progress_from_s, 1) + " s; timeout after " +
           fixed(e.sim_time_s, 1) + " s, " + left;
  }
  return "timeout: not reached after " + fixed(e.sim_time_s, 1) + " s, " + left;
}

// The services of one vehicle (one channel prefix) and the observer that records its flight.
struct Vehicle {
  StackOptions options;  // with this vehicle's prefix and seeds
  std::unique_ptr<PlannerHost> host;
  std::unique_ptr<SimNode> sim;
  std::unique_ptr<SetpointNode> setpoint;  // --follow setpoint
  std::optional<MissionSequencer> mission;
  ServiceContext* observer = nullptr;
  FlightRecord record;
  StopCensusBuilder census;
  int current_mode = 0;
  int64_t t0 = 0, next_sample = 0;
  bool done = false;
  std::string rejected_detail, unreachable_detail;  // the arbiter's last words on the goal

  Vehicle(lcm::LCM& bus, const StackOptions& opts) : options(opts) {
    PlannerHostOptions h;
    h.config = options.config;
    h.prefix = options.prefix;
    h.policy = options.policy;
    h.map_loss = options.map_loss;
    h.loss_seed = options.loss_seed;
    // Planners first, simulator last: when the simulator publishes, everyone already listens.
    host = std::make_unique<PlannerHost>(h, &bus);
    if (options.sim.follow == "setpoint") {
      setpoint = std::make_unique<SetpointNode>(host->addContext("mmh-setpoint"), options.config);
    }
    if (!options.waypoints.empty()) {
      mission.emplace(options.waypoints, loadMissionRules(options.config).stop_speed_mps);
    }
    sim = std::make_unique<SimNode>(host->addContext("mmh-sim"), options.config, options.sim);
    observer = &host->addContext("mmh-stack");
    observer->subscribe(channels::kPlanResult, &Vehicle::onPlanResult, this);
    observer->subscribe(channels::kTrajectory, &Vehicle::onTrajectory, this);
    observer->subscribe(channels::kArbiterStatus, &Vehicle::onStatus, this);
    host->markRunning();
  }

  void publishGoal() {
    goal_t goal{};
    goal.header.utime = sim->nowUtime();
    goal.goal_id = 1;
    fromVec3(options.sim.goal, goal.position);
    if (mission) {
      const Waypoint& w = mission->current();
      goal.goal_id = 1 + mission->index();
      fromVec3(w.position, goal.position);
      goal.waypoint_index = mission->index();
      goal.num_waypoints = mission->size();
      goal.tolerance_m = w.tolerance_m;
      goal.stop = w.stop;
    }
    observer->clock().observe(goal.header.utime);
    observer->publish(channels::kGoal, goal);
  }

  // After a simulation step: heartbeats and the 10 Hz path sample.
  void afterStep() {
    const int64_t now = sim->nowUtime();
    if (setpoint) setpoint->tick(now);
    if (mission) {
      const KinematicState& s = sim->simulator().vehicle().state();
      if (mission->update(s.position, s.velocity) && !mission->finished()) publishGoal();
    }
    host->advanceClocks(now);
    host->publishHeartbeats(now);
    if (now >= next_sample) {
      next_sample += 100'000;
      const auto& v = sim->simulator().vehicle();
      PathSample p;
      p.t = (now - t0) * 1e-6;
      p.position = v.state().position;
      p.speed = v.state().velocity.norm();
      p.mode = current_mode;
      p.energy = sim->metrics().energy;
      record.path.push_back(p);
      census.onProgress(sinceStart(now), (p.position - options.sim.goal).norm(), p.speed);
    }
  }

  void finish(double wall_time_s) {
    record.metrics = sim->metrics();
    record.sim_time_s = (sim->nowUtime() - t0) * 1e-6;
    record.end_reason =
        record.metrics.collided ? "collided" : (record.metrics.reached ? "reached" : "timeout");
    record.wall_time_s = wall_time_s;
    record.census = census.finish(sinceStart(sim->nowUtime()));
    FailureEvidence e;
    e.reached = record.metrics.reached;
    e.collided = record.metrics.collided;
    e.collision_time_s = record.metrics.collision_utime >= 0
                             ? sinceStart(record.metrics.collision_utime)
                             : record.sim_time_s;
    e.collision_position = record.metrics.collision_position;
    e.sim_time_s = record.sim_time_s;
    e.distance_to_goal_m = (sim->simulator().vehicle().state().position - options.sim.goal).norm();
    e.rejected_detail = rejected_detail;
    e.unreachable_detail = unreachable_detail;
    e.longest_no_progress_s = record.census.longest_no_progress_s;
    e.longest_no_progress_from_s = record.census.longest_no_progress_from_s;
    record.failure_reason = failureReason(e);
    done = true;
  }

  // Simulated seconds since the start of the flight (the census and the plan calls share it).
  double sinceStart(int64_t utime) const { return (utime - options.sim.start_utime) * 1e-6; }

  // Observer handlers: what the benchmark needs to know about planning.
  void onPlanResult(const plan_result_t& msg) {
    PlanCall c;
    c.mode = msg.mode;
    c.ok = msg.status == plan_result_t::STATUS_OK;
    c.reason = msg.reason;
    c.compute_ms = msg.compute_us * 1e-3;
    c.sim_time_s = sinceStart(sim->nowUtime());
    record.calls.push_back(c);
    census.onPlanResult(msg.mode, c.ok, msg.reason, msg.detail);
    if (msg.mode >= 1 && msg.mode <= 4) ++record.iterations[msg.mode];
  }
  void onTrajectory(const trajectory_t& msg) {
    current_mode = msg.source_mode;
    ++record.commits;
    std::vector<uint8_t> bytes(static_cast<size_t>(msg.getEncodedSize()));
    msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    for (uint8_t b : bytes)
      record.trajectory_digest = (record.trajectory_digest ^ b) * 1099511628211ull;
  }
  void onStatus(const arbiter_status_t& msg) {
    if (msg.outcome == arbiter_status_t::OUTCOME_FAILED) ++record.failed_decisions;
    // A stop is the vehicle starting to brake: a stop committed, or a backup stop reached.
    if (msg.outcome == arbiter_status_t::OUTCOME_STOPPING) ++record.stops;
    const std::string detail = msg.detail.empty() ? "(no detail)" : msg.detail;
    if (msg.outcome == arbiter_status_t::OUTCOME_REJECTED) rejected_detail = detail;
    if (msg.outcome == arbiter_status_t::OUTCOME_UNREACHABLE) unreachable_detail = detail;
    // A goal accepted later (moved, committed to) is no longer refused.
    if (msg.outcome == arbiter_status_t::OUTCOME_COMMITTED ||
        msg.outcome == arbiter_status_t::OUTCOME_GOAL_MOVED) {
      rejected_detail.clear();
    }
    DecisionSample d;
    d.time_s = sinceStart(sim->nowUtime());
    d.trigger = msg.trigger;
    d.outcome = msg.outcome;
    d.modes_asked = msg.modes_asked;
    d.detail = msg.detail;
    census.onDecision(d);
  }
};

struct Stack::Impl {
  StackOptions options;
  std::unique_ptr<lcm::LCM> lcm;
  std::vector<std::unique_ptr<Vehicle>> vehicles;
  std::unique_ptr<Recorder> recorder;

  void drain() {
    while (lcm->handleTimeout(0) > 0) {
    }
  }
};

Stack::Stack(const StackOptions& options) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.options = options;
  if (options.vehicles < 1) throw std::runtime_error("mmh-stack: at least one vehicle");
  s.lcm = openLcm("memq://");
  for (int i = 0; i < options.vehicles; ++i) {
    StackOptions v = options;
    v.prefix = vehiclePrefix(i);
    v.sim.seed = options.sim.seed + i;
    v.sim.noise_seed = options.sim.noise_seed + i;
    s.vehicles.push_back(std::make_unique<Vehicle>(*s.lcm, v));
  }
  if (!options.log_path.empty()) {
    s.recorder = std::make_unique<Recorder>(options.log_path, &s.vehicles[0]->sim->simulator());
    s.lcm->subscribe(".*", &Recorder::onRaw, s.recorder.get());
  }
}

Stack::~Stack() = default;

std::string Stack::vehiclePrefix(int i) const {
  const StackOptions& o = impl_->options;
  return o.vehicles == 1 ? o.prefix : o.prefix + "UAV" + std::to_string(i + 1) + "_";
}

FlightRecord Stack::fly() {
  return flyAll().front();
}

std::vector<FlightRecord> Stack::flyAll(const std::function<void(double)>& on_second) {
  Impl& s = *impl_;
  const auto wall_start = std::chrono::steady_clock::now();
  auto wall = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  };
  for (auto& v : s.vehicles) v->publishGoal();
  s.drain();
  for (auto& v : s.vehicles) v->t0 = v->next_sample = v->sim->nowUtime();
  const int64_t t0 = s.vehicles[0]->t0;
  const int64_t limit = t0 + static_cast<int64_t>(s.options.timeout_s * 1e6);
  int64_t next_second = t0 + 1'000'000;
  size_t running = s.vehicles.size();
  while (running > 0) {
    // Every simulator steps, then every message is delivered: one lock-step for all vehicles.
    for (auto& v : s.vehicles) {
      if (!v->done) v->sim->step();
    }
    s.drain();
    for (auto& v : s.vehicles) {
      if (!v->done) v->afterStep();
    }
    s.drain();
    for (auto& v : s.vehicles) {
      if (!v->done && (v->sim->finished() || v->sim->nowUtime() >= limit)) {
        v->finish(wall());
        --running;
      }
    }
    int64_t now = t0;  // the simulators step together; finished ones stay behind
    for (auto& v : s.vehicles) now = std::max(now, v->sim->nowUtime());
    if (on_second && now >= next_second) {
      next_second += 1'000'000;
      on_second((now - t0) * 1e-6);
    }
  }
  std::vector<FlightRecord> out;
  for (auto& v : s.vehicles) out.push_back(v->record);
  return out;
}

}  // namespace mmh
