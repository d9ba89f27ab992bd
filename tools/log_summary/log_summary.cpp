#include "log_summary.hpp"

#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <stdexcept>

#include <nlohmann/json.hpp>
#include <set>

#include "mmh/arbiter_status_t.hpp"
#include "mmh/common/decision_names.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/goal_t.hpp"
#include "mmh/local_map_t.hpp"
#include "mmh/mission_status_t.hpp"
#include "mmh/odometry_t.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/plan_result_t.hpp"
#include "mmh/trajectory_t.hpp"

namespace mmh {
namespace {

const std::vector<std::string>& knownChannels() {
  static const std::vector<std::string> names = {
      "ODOMETRY",         "POINTCLOUD",       "GOAL",
      "LOCAL_MAP",        "AWARENESS",        "PLAN_REQUEST_FPM",
      "PLAN_REQUEST_SOM", "PLAN_REQUEST_EAM", "PLAN_RESULT",
      "TRAJECTORY",       "ARBITER_STATUS",   "HEARTBEAT",
      "MISSION_STATUS"};
  return names;
}

// Splits "UAV1_LOCAL_MAP" into ("UAV1_", "LOCAL_MAP"); unknown channels keep their full name.
std::pair<std::string, std::string> splitChannel(const std::string& channel) {
  for (const std::string& base : knownChannels()) {
    if (channel.size() >= base.size() &&
        channel.compare(channel.size() - base.size(), base.size(), base) == 0) {
      return {channel.substr(0, channel.size() - base.size()), base};
    }
  }
  return {"", channel};
}

template <class Msg>
bool decode(const lcm::LogEvent& e, Msg& msg) {
  try {
    return msg.decode(e.data, 0, e.datalen) >= 0;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace

double ChannelStats::rateHz() const {
  const double span = (last_us - first_us) * 1e-6;
  return messages > 1 && span > 0 ? (messages - 1) / span : 0.0;
}

Percentiles percentiles(std::vector<double> v) {
  Percentiles p;
  p.count = static_cast<int64_t>(v.size());
  if (v.empty()) return p;
  std::sort(v.begin(), v.end());
  auto at = [&](double q) {
    const double idx = q * (v.size() - 1);
    const size_t lo = static_cast<size_t>(std::floor(idx)), hi = std::min(v.size() - 1, lo + 1);
    return v[lo] + (v[hi] - v[lo]) * (idx - lo);
  };
  p.p50 = at(0.5);
  p.p90 = at(0.9);
  p.p99 = at(0.99);
  p.max = v.back();
  double sum = 0;
  for (double x : v) sum += x;
  p.mean = sum / v.size();
  return p;
}

LogSummary summarizeLog(const std::string& path) {
  lcm::LogFile log(path, "r");
  if (!log.good()) throw std::runtime_error("cannot read LCM log " + path);
  LogSummary s;
  s.path = path;
  // Per vehicle: request id -> (request time, mode), and the last map_seq seen.
  std::map<std::string, std::map<int64_t, std::pair<int64_t, int>>> open_requests;
  std::map<std::string, int64_t> last_map_seq;
  std::map<std::string, double> delta_bytes_sum;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    ++s.events;
    if (s.first_us == 0) s.first_us = e->timestamp;
    s.last_us = e->timestamp;
    const auto [prefix, base] = splitChannel(e->channel);
    VehicleSummary& v = s.vehicles[prefix];
    ChannelStats& c = v.channels[base];
    if (c.messages == 0) c.first_us = e->timestamp;
    c.last_us = e->timestamp;
    ++c.messages;
    c.bytes += e->datalen;
    if (base.rfind("PLAN_REQUEST_", 0) == 0) {
      plan_request_t m;
      if (!decode(*e, m)) {
        ++c.undecodable;
        continue;
      }
      ++v.requests;
      open_requests[prefix][m.request_id] = {e->timestamp, m.mode};
    } else if (base == "PLAN_RESULT") {
      plan_result_t m;
      if (!decode(*e, m)) {
        ++c.undecodable;
        continue;
      }
      ModeStats& ms = v.modes[m.mode];
      ++ms.results;
      if (m.status == plan_result_t::STATUS_OK)
        ++ms.ok;
      else {
        ++ms.failed;
        ++ms.failure_reasons[m.reason];
      }
      ms.compute_ms.push_back(m.compute_us * 1e-3);
      auto& open = open_requests[prefix];
      auto it = open.find(m.request_id);
      if (it != open.end()) {
        ms.latency_ms.push_back((e->timestamp - it->second.first) * 1e-3);
        open.erase(it);
      }
    } else if (base == "LOCAL_MAP") {
      local_map_t m;
      if (!decode(*e, m)) {
        ++c.undecodable;
        continue;
      }
      if (m.kind == local_map_t::KIND_KEYFRAME) {
        ++v.map_keyframes;
        v.map_keyframe_bytes_max = std::max<int64_t>(v.map_keyframe_bytes_max, e->datalen);
      } else {
        ++v.map_deltas;
        v.map_delta_bytes_max = std::max<int64_t>(v.map_delta_bytes_max, e->datalen);
        delta_bytes_sum[prefix] += e->datalen;
      }
      auto it = last_map_seq.find(prefix);
      if (it != last_map_seq.end() && m.map_seq > it->second + 1) {
        ++v.map_gaps;
        v.map_missing += m.map_seq - it->second - 1;
      }
      last_map_seq[prefix] = m.map_seq;
    } else if (base == "ARBITER_STATUS") {
      arbiter_status_t m;
      if (!decode(*e, m)) {
        ++c.undecodable;
        continue;
      }
      ++v.outcomes[m.outcome];
      if (m.degraded) ++v.degraded_decisions;
      v.max_answer_deadline_s = std::max(v.max_answer_deadline_s, m.answer_deadline_s);
      v.decisions.push_back({(e->timestamp - s.first_us) * 1e-6, m.trigger, m.outcome,
                             m.committed_mode, m.awareness_safe != 0, m.position[0], m.position[1],
                             m.detail, -1});
      if (m.outcome == arbiter_status_t::OUTCOME_COMMITTED ||
          m.outcome == arbiter_status_t::OUTCOME_STOPPING)
        ++v.commits[m.committed_mode];
      if (m.threat_seen_utime > 0) {
        const bool real_time = std::abs(e->timestamp - m.header.utime) < 1'000'000;
        const int64_t answered = real_time ? e->timestamp : m.header.utime;
        v.reaction_ms.push_back((answered - m.threat_seen_utime) * 1e-3);
        v.decisions.back().reaction_ms = v.reaction_ms.back();
      }
    } else if (base == "MISSION_STATUS") {
      mission_status_t m;
      if (!decode(*e, m)) {
        ++c.undecodable;
        continue;
      }
      v.mission_seen = true;
      v.reached = m.reached;
      v.collided = m.collided;
      v.flight_time_s = m.flight_time_s;
      v.distance_m = m.distance_m;
      v.energy = m.energy;
    }
  }
  for (auto& [prefix, v] : s.vehicles) {
    v.unanswered_requests = static_cast<int64_t>(open_requests[prefix].size());
    if (v.map_deltas > 0) v.map_delta_bytes_mean = delta_bytes_sum[prefix] / v.map_deltas;
  }
  return s;
}

void printSummary(const LogSummary& s, std::ostream& out) {
  out << std::fixed << std::setprecision(2);
  out << "log " << s.path << ": " << s.events << " events over " << (s.last_us - s.first_us) * 1e-6
      << " s\n";
  for (const auto& [prefix, v] : s.vehicles) {
    out << "\n== vehicle prefix '" << prefix << "'\n";
    out << "channel                 messages   rate_hz   mean_kB  undecodable\n";
    for (const auto& [name, c] : v.channels) {
      out << std::left << std::setw(22) << name << std::right << std::setw(10) << c.messages
          << std::setw(10) << c.rateHz() << std::setw(10)
          << (c.messages ? c.bytes / 1024.0 / c.messages : 0.0) << std::setw(13) << c.undecodable
          << "\n";
    }
    if (!v.modes.empty()) {
      out << "\nplanning   calls    ok  failed   compute_ms p50/p99/max     latency_ms "
             "p50/p90/p99/max\n";
      int64_t total = 0;
      for (const auto& [mode, m] : v.modes) {
        total += m.results;
        const Percentiles c = percentiles(m.compute_ms), l = percentiles(m.latency_ms);
        out << std::left << std::setw(8) << modeName(mode) << std::right << std::setw(8)
            << m.results << std::setw(6) << m.ok << std::setw(8) << m.failed << "   " << c.p50
            << " / " << c.p99 << " / " << c.max << "      " << l.p50 << " / " << l.p90 << " / "
            << l.p99 << " / " << l.max << "\n";
      }
      out << "total planning iterations: " << total << "; requests " << v.requests
          << ", unanswered " << v.unanswered_requests << "\n";
    }
    if (v.map_keyframes + v.map_deltas > 0) {
      out << "\nLOCAL_MAP: " << v.map_keyframes << " keyframes (max "
          << v.map_keyframe_bytes_max / 1024.0 << " kB), " << v.map_deltas << " deltas (mean "
          << v.map_delta_bytes_mean / 1024.0 << " kB, max " << v.map_delta_bytes_max / 1024.0
          << " kB), gaps in map_seq: " << v.map_gaps << " (" << v.map_missing
          << " messages missing)\n";
    }
    if (!v.outcomes.empty()) {
      out << "arbiter decisions:";
      for (const auto& [o, n] : v.outcomes) out << " " << outcomeName(o) << "=" << n;
      out << "; commits by mode:";
      for (const auto& [m, n] : v.commits) out << " " << modeName(m) << "=" << n;
      out << "\n";
      out << "arbiter degraded: " << v.degraded_decisions << " decisions (longest answer deadline "
          << v.max_answer_deadline_s * 1e3 << " ms)\n";
      const Percentiles r = percentiles(v.reaction_ms);
      out << "newly mapped danger -> answer committed: " << v.reaction_ms.size()
          << " reactions, ms p50/p90/p99/max " << r.p50 << " / " << r.p90 << " / " << r.p99 << " / "
          << r.max << "\n";
    }
    if (v.mission_seen) {
      out << "mission: " << (v.reached ? "reached" : "not reached")
          << (v.collided ? ", COLLIDED" : "") << ", flight time " << v.flight_time_s
          << " s, distance " << v.distance_m << " m, energy " << v.energy << " m^2/s^5\n";
    }
  }
}

void printDecisions(const LogSummary& s, std::ostream& out) {
  out << std::fixed << std::setprecision(2);
  for (const auto& [prefix, v] : s.vehicles) {
    for (const DecisionLine& d : v.decisions) {
      out << prefix << std::setw(8) << d.t_s << " s  (" << std::setw(6) << d.x << ", "
          << std::setw(6) << d.y << ")  S=" << (d.safe ? "1" : "0") << "  "
          << triggerName(d.trigger) << " -> " << outcomeName(d.outcome) << " "
          << modeName(d.committed_mode) << "  " << d.detail;
      if (d.reaction_ms >= 0) out << "  [danger seen " << d.reaction_ms << " ms before]";
      out << "\n";
    }
  }
}

void exportFlight(const std::string& log_path, const std::string& prefix, std::ostream& out) {
  lcm::LogFile log(log_path, "r");
  if (!log.good()) throw std::runtime_error("cannot read LCM log " + log_path);
  nlohmann::json j;
  auto& path = j["path"] = nlohmann::json::array();            // t, x, y, z, speed, mode
  auto& decisions = j["decisions"] = nlohmann::json::array();  // t, x, y, mode, trigger
  std::set<std::pair<int, int>> occupied;                      // global voxel x, y
  LocalMapReceiver map;
  double resolution = 0.1;
  int mode = 0;
  int64_t t0 = -1, next_sample = 0;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    const auto [p, base] = splitChannel(e->channel);
    if (p != prefix) continue;
    if (base == "ODOMETRY") {
      odometry_t m;
      if (!decode(*e, m)) continue;
      if (t0 < 0) t0 = m.header.utime;
      if (m.header.utime < next_sample) continue;
      next_sample = m.header.utime + 100'000;
      const double speed = std::sqrt(m.velocity[0] * m.velocity[0] + m.velocity[1] * m.velocity[1] +
                                     m.velocity[2] * m.velocity[2]);
      path.push_back(
          {(m.header.utime - t0) * 1e-6, m.position[0], m.position[1], m.position[2], speed, mode});
    } else if (base == "TRAJECTORY") {
      trajectory_t m;
      if (decode(*e, m)) mode = m.source_mode;
    } else if (base == "ARBITER_STATUS") {
      arbiter_status_t m;
      if (!decode(*e, m) || (m.outcome != arbiter_status_t::OUTCOME_COMMITTED &&
                             m.outcome != arbiter_status_t::OUTCOME_STOPPING))
        continue;
      decisions.push_back({t0 < 0 ? 0.0 : (m.header.utime - t0) * 1e-6, m.position[0],
                           m.position[1], m.committed_mode, m.trigger});
    } else if (base == "GOAL") {
      goal_t m;
      if (decode(*e, m)) j["goal"] = {m.position[0], m.position[1], m.position[2]};
    } else if (base == "MISSION_STATUS") {
      mission_status_t m;
      if (!decode(*e, m)) continue;
      j["mission"] = {{"reached", m.reached},
                      {"collided", m.collided},
                      {"flight_time_s", m.flight_time_s},
                      {"distance_m", m.distance_m},
                      {"energy", m.energy}};
    } else if (base == "LOCAL_MAP") {
      local_map_t m;
      if (!decode(*e, m) || map.apply(m) != LocalMapReceiver::Result::kApplied) continue;
      const VoxelGrid& g = map.grid();
      resolution = g.resolution();
      auto add = [&](int64_t i) {
        if (g.atLinear(i) != Occupancy::kOccupied) return;
        const Eigen::Vector3i global = g.originIndex() + g.localFromLinear(i);
        occupied.insert({global.x(), global.y()});
      };
      if (map.lastWasKeyframe()) {
        for (int64_t i = 0; i < g.numCells(); ++i) add(i);
      } else {
        for (int64_t i : map.lastChangedCells()) add(i);
      }
    }
  }
  j["resolution_m"] = resolution;
  auto& cells = j["occupied_xy"] = nlohmann::json::array();
  for (const auto& [x, y] : occupied) cells.push_back({x, y});
  out << j.dump() << "\n";
}

}  // namespace mmh
