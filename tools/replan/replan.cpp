#include "replan.hpp"

#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <regex>

#include "eam_node.hpp"
#include "fpm_node.hpp"
#include "mmh/common/checked_decode.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/common/plan_status.hpp"
#include "mmh/eam/planner.hpp"
#include "mmh/local_map_t.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/plan_result_t.hpp"
#include "mmh/som/planner.hpp"

namespace mmh {
namespace {

// --samples: time between two samples of a trajectory (s).
constexpr double kSampleStepS = 0.05;

struct Answer {
  bool ok = false;
  std::string detail;
  Trajectory trajectory;  // when ok
  // For --samples: what the mode searched and, when it failed, what it refused.
  Trajectory refused;
  std::string refused_what;  // what `refused` is
  std::vector<std::vector<Eigen::Vector3d>> paths;
  std::vector<Eigen::Vector3d> junctions;  // SOM's corridor
};

Answer answerOf(bool ok, const char* status, const std::string& detail,
                const Trajectory& trajectory) {
  Answer a;
  a.ok = ok;
  a.detail = ok ? "" : std::string(status) + ": " + detail;
  a.trajectory = trajectory;
  return a;
}

// The mode's planner behind one signature: the map and the request message.
using PlanFn = std::function<Answer(const VoxelGrid&, const plan_request_t&)>;

struct ModePlanner {
  std::string request_channel;
  int8_t wire_mode = 0;
  PlanFn plan;
  // What a new keyframe prepares; none for a mode that plans without a map (FPM).
  std::function<void(const VoxelGrid&)> prepare;
};

ModePlanner makePlanner(const std::string& mode, const ReplanOptions& options) {
  const Config& config = options.config;
  if (mode == "eam") {
    auto planner = std::make_shared<eam::Planner>(eam::loadEamParams(config));
    return {channels::kPlanRequestEam, plan_request_t::MODE_EAM,
            [planner, &options](const VoxelGrid& grid, const plan_request_t& msg) {
              const bool traced =
                  options.trace != nullptr && msg.request_id == options.trace_request_id;
              planner->setTrace(traced ? std::function<void(const std::string&)>(
                                             [&options](const std::string& line) {
                                               *options.trace << "  " << line << "\n";
                                             })
                                       : nullptr);
              const eam::PlanResult r = planner->plan(grid, eamRequestOf(msg));
              Answer a = answerOf(r.ok, toString(r.reason), r.detail, r.trajectory);
              if (!r.ok && r.spline.numControlPoints() > 0) {
                a.refused = r.spline.toTrajectory();
                a.refused_what = "EAM's last curve (not verified)";
              }
              a.paths = r.guide_paths;
              return a;
            },
            [planner](const VoxelGrid& grid) { planner->prepare(grid); }};
  }
  if (mode == "som") {
    auto planner = std::make_shared<som::Planner>(som::loadSomParams(config));
    return {channels::kPlanRequestSom, plan_request_t::MODE_SOM,
            [planner](const VoxelGrid& grid, const plan_request_t& msg) {
              const som::PlanOutput r =
                  planner->plan(grid, startStateOf(msg), toVec3(msg.target), msg.max_speed_mps);
              Answer a = answerOf(r.ok(), toString(r.status), r.detail, r.trajectory);
              a.refused = r.refused;
              a.refused_what = "the trajectory SOM's verification refused";
              if (!r.path.empty()) a.paths.push_back(r.path);
              a.junctions = r.corridor.junctions;
              return a;
            },
            [planner](const VoxelGrid& grid) { planner->prepare(grid); }};
  }
  if (mode == "fpm") {
    auto planner = std::make_shared<fpm::Planner>(fpm::loadParams(config));
    return {channels::kPlanRequestFpm, plan_request_t::MODE_FPM,
            [planner](const VoxelGrid&, const plan_request_t& msg) {
              const fpm::Result r = planner->plan(fpmRequestOf(msg));
              return answerOf(r.ok, toString(r.status), r.detail, r.trajectory);
            },
            nullptr};
  }
  throw ReplanInputError("unknown mode '" + mode + "' (eam, som or fpm)");
}

template <class Msg>
bool decodeEvent(const lcm::LogEvent& e, Msg* msg) {
  std::string why;
  return decodeChecked(e.data, static_cast<uint32_t>(e.datalen), *msg, &why) == DecodeOutcome::kOk;
}

std::string pointText(const Eigen::Vector3d& p) {
  char text[64];
  std::snprintf(text, sizeof(text), "(%.2f, %.2f, %.2f)", p.x(), p.y(), p.z());
  return text;
}

// --samples: the request, what the mode searched, and its answer or what it refused.
void printRequestSamples(const plan_request_t& msg, double t_s, const std::string& mode,
                         const Answer& a, std::ostream& out) {
  const KinematicState start = startStateOf(msg);
  char line[320];
  std::snprintf(line, sizeof(line),
                "request %lld at %.2f s (%s): start %s m, velocity %s m/s, acceleration %s m/s^2; "
                "target %s\n",
                static_cast<long long>(msg.request_id), t_s, mode.c_str(),
                pointText(start.position).c_str(), pointText(start.velocity).c_str(),
                pointText(start.acceleration).c_str(), pointText(toVec3(msg.target)).c_str());
  out << line << "now: " << (a.ok ? "answered" : "failed: " + a.detail) << "\n";
  for (const auto& path : a.paths) {
    out << (mode == "som" ? "A* path" : "A* guide") << " (" << path.size() << " points):";
    for (const Eigen::Vector3d& p : path) out << " " << pointText(p);
    out << "\n";
  }
  if (!a.junctions.empty()) {
    out << "corridor junctions (" << a.junctions.size() << "):";
    for (const Eigen::Vector3d& p : a.junctions) out << " " << pointText(p);
    out << "\n";
  }
  const Trajectory& shown = a.ok ? a.trajectory : a.refused;
  if (shown.empty()) return;
  std::snprintf(line, sizeof(line),
                "%s: %zu pieces, %.2f s, top speed %.2f m/s, top acceleration "
                "%.2f m/s^2\n",
                a.ok ? "answer" : a.refused_what.c_str(), shown.pieces().size(), shown.duration(),
                shown.maxSpeed(), shown.maxAcceleration());
  out << line;
  printTrajectorySamples(shown, kSampleStepS, out);
}

}  // namespace

void printTrajectorySamples(const Trajectory& t, double step_s, std::ostream& out) {
  out << "      t        x        y        z    speed      acc     jerk\n";
  if (t.empty() || !(step_s > 0.0)) return;
  auto row = [&](double s) {
    const Eigen::Vector3d p = t.position(s);
    char line[128];
    std::snprintf(line, sizeof(line), "%7.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f\n", s, p.x(),
                  p.y(), p.z(), t.velocity(s).norm(), t.acceleration(s).norm(), t.jerk(s).norm());
    out << line;
  };
  const double end = t.duration();
  const int steps = static_cast<int>(std::floor(end / step_s + 1e-9));
  for (int i = 0; i <= steps; ++i) row(i * step_s);
  if (end - steps * step_s > 1e-9) row(end);
}

std::vector<ReplanOutcome> replanLog(const std::string& log_path, const ReplanOptions& options) {
  ModePlanner planner = makePlanner(options.mode, options);
  lcm::LogFile log(log_path, "r");
  if (!log.good()) throw ReplanInputError("cannot read LCM log " + log_path);
  const std::string map_channel = options.prefix + channels::kLocalMap;
  const std::string request_channel = options.prefix + planner.request_channel;
  const std::string result_channel = options.prefix + channels::kPlanResult;
  LocalMapReceiver map(options.config.getDouble("map.inflation_m"));
  std::vector<ReplanOutcome> outcomes;
  std::map<int64_t, size_t> pending;  // request id -> index into outcomes
  int64_t t0 = -1;
  for (const lcm::LogEvent* e = log.readNextEvent(); e != nullptr; e = log.readNextEvent()) {
    if (t0 < 0) t0 = e->timestamp;
    if (e->channel == map_channel) {
      local_map_t msg;
      if (decodeEvent(*e, &msg) && map.apply(msg) == LocalMapReceiver::Result::kApplied &&
          map.lastWasKeyframe() && planner.prepare)
        planner.prepare(map.grid());
    } else if (e->channel == request_channel) {
      plan_request_t msg;
      if (!decodeEvent(*e, &msg) || msg.mode != planner.wire_mode) continue;
      ReplanOutcome o;
      o.t_s = 1e-6 * static_cast<double>(e->timestamp - t0);
      o.request_id = msg.request_id;
      o.start_speed_mps = toVec3(msg.start_velocity).norm();
      o.start_acceleration_mps2 = toVec3(msg.start_acceleration).norm();
      if (map.hasMap() || !planner.prepare) {
        const auto started = std::chrono::steady_clock::now();
        const Answer a = planner.plan(map.grid(), msg);
        o.compute_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started)
                .count();
        o.ok = a.ok;
        o.detail = a.detail;
        if (options.samples && msg.request_id == options.samples_request_id)
          printRequestSamples(msg, o.t_s, options.mode, a, *options.samples);
        o.target_distance_m = (toVec3(msg.target) - toVec3(msg.start_position)).norm();
        if (a.ok) {
          o.duration_s = a.trajectory.duration();
          o.length_m = a.trajectory.arcLength();
          o.max_speed_mps = a.trajectory.maxSpeed();
          o.jerk_energy = a.trajectory.jerkEnergy();
        }
      } else {
        o.detail = "no LOCAL_MAP before the request";
      }
      pending[o.request_id] = outcomes.size();
      outcomes.push_back(o);
    } else if (e->channel == result_channel) {
      plan_result_t msg;
      if (!decodeEvent(*e, &msg) || msg.mode != planner.wire_mode) continue;
      const auto it = pending.find(msg.request_id);
      if (it == pending.end()) continue;
      ReplanOutcome& o = outcomes[it->second];
      o.logged_answer = true;
      o.logged_ok = msg.status == plan_result_t::STATUS_OK;
      o.logged_detail = o.logged_ok ? "" : msg.detail;
      pending.erase(it);
    }
  }
  return outcomes;
}

std::string failureKind(const std::string& detail) {
  static const std::regex kNumber(R"([0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?)");
  const std::string kind = std::regex_replace(detail, kNumber, "#");
  // The step timings in brackets differ between any two calls: not part of the kind.
  const size_t bracket = kind.find(" [");
  return bracket == std::string::npos ? kind : kind.substr(0, bracket);
}

ReplanSummary summarize(const std::vector<ReplanOutcome>& outcomes) {
  ReplanSummary s;
  double total_ms = 0.0;
  for (const ReplanOutcome& o : outcomes) {
    if (!o.logged_answer) {
      ++s.unanswered;
      continue;
    }
    ++s.requests;
    total_ms += o.compute_ms;
    s.max_compute_ms = std::max(s.max_compute_ms, o.compute_ms);
    if (!o.logged_ok) ++s.failed_before;
    if (!o.ok) {
      ++s.failed_now;
      ++s.reasons_now[failureKind(o.detail)];
    } else {
      s.answered_length_m += o.length_m;
      s.answered_duration_s += o.duration_s;
      s.mean_jerk_energy += o.jerk_energy;
    }
    if (!o.logged_ok && o.ok) ++s.fixed;
    if (o.logged_ok && !o.ok) ++s.broken;
  }
  if (s.requests > 0) s.mean_compute_ms = total_ms / s.requests;
  const int answered = s.requests - s.failed_now;
  if (answered > 0) s.mean_jerk_energy /= answered;
  if (s.answered_duration_s > 0.0) s.mean_speed_mps = s.answered_length_m / s.answered_duration_s;
  return s;
}

void printReplanSummary(const ReplanSummary& s, std::ostream& out) {
  char line[256];
  std::snprintf(line, sizeof(line),
                "requests %d (and %d without a logged answer)\nfailed then %d, now %d: %d "
                "fixed, %d broken\ncompute now: mean %.2f ms, max %.2f ms\n",
                s.requests, s.unanswered, s.failed_before, s.failed_now, s.fixed, s.broken,
                s.mean_compute_ms, s.max_compute_ms);
  out << line;
  if (s.requests > s.failed_now) {
    std::snprintf(line, sizeof(line),
                  "answers now: %.1f m in %.1f s (mean speed %.2f m/s), mean energy %.1f "
                  "m^2/s^5\n",
                  s.answered_length_m, s.answered_duration_s, s.mean_speed_mps, s.mean_jerk_energy);
    out << line;
  }
  if (!s.reasons_now.empty()) out << "failures now by kind:\n";
  std::vector<std::pair<int, std::string>> kinds;
  for (const auto& [kind, n] : s.reasons_now) kinds.emplace_back(n, kind);
  std::sort(kinds.begin(), kinds.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  for (const auto& [n, kind] : kinds) out << "  " << n << "  " << kind << "\n";
}

}  // namespace mmh
