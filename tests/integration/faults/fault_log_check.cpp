// mmh-fault-log-check: reads the LCM log of a fault-injection flight and checks what the fault
// tests promise: every committed TRAJECTORY takes over without a jump from the one it follows (as
// on the vehicle: the latest sent that starts before it), no planning mode's trajectory is
// committed while ODOMETRY is stale, the mission was reached without collision, and the expected
// ARBITER_STATUS details (or degraded reasons) and HEARTBEAT counters appeared. With
// --wait-distance D it instead waits (re-reading the growing log) until MISSION_STATUS shows D
// metres flown, so that a test injects its fault mid-flight whatever the machine's load; with
// --wait-status TEXT, until some ARBITER_STATUS detail contains TEXT (the fault was noticed).
#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "mmh/arbiter_status_t.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/heartbeat_t.hpp"
#include "mmh/mission_status_t.hpp"
#include "mmh/odometry_t.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/trajectory_t.hpp"

namespace {

struct Options {
  std::string log;
  std::vector<std::string> statuses;  // substrings some ARBITER_STATUS detail must contain
  std::vector<std::string> counters;  // SERVICE:COUNTER that must be > 0 in some HEARTBEAT
  double stale_odometry_s = 0.5;      // a mode's commit later than this after ODOMETRY fails
  double jump_position_m = 0.01;
  double jump_velocity_mps = 0.05;
  double wait_distance_m = -1.0;  // >= 0: only wait until this distance was flown
  std::string wait_status;        // not empty: only wait until an ARBITER_STATUS says this
  double wait_timeout_s = 90.0;
};

template <class Msg>
bool decode(const lcm::LogEvent& e, Msg* msg) {
  return msg->decode(e.data, 0, static_cast<int>(e.datalen)) >= 0;
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

int usage() {
  std::cerr << "usage: mmh-fault-log-check LOG [--expect-status TEXT]... "
               "[--expect-counter SERVICE:NAME]... [--stale-odometry-s S]\n"
               "       mmh-fault-log-check LOG --wait-distance M [--timeout S]\n"
               "       mmh-fault-log-check LOG --wait-status TEXT [--timeout S]\n";
  return 2;
}

// Largest distance flown in the log's MISSION_STATUS messages so far.
double distanceFlown(const std::string& path) {
  lcm::LogFile log(path, "r");
  double d = 0.0;
  if (!log.good()) return d;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    mmh::mission_status_t m;
    if (endsWith(e->channel, "MISSION_STATUS") && decode(*e, &m)) d = std::max(d, m.distance_m);
  }
  return d;
}

// Whether an ARBITER_STATUS says `text`: in the detail of its decision, or in the reason its
// latency budget is degraded.
bool statusSays(const mmh::arbiter_status_t& m, const std::string& text) {
  return m.detail.find(text) != std::string::npos ||
         m.degraded_reason.find(text) != std::string::npos;
}

// Whether some ARBITER_STATUS in the log so far says `text` (statusSays).
bool statusSeen(const std::string& path, const std::string& text) {
  lcm::LogFile log(path, "r");
  if (!log.good()) return false;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    mmh::arbiter_status_t m;
    if (endsWith(e->channel, "ARBITER_STATUS") && decode(*e, &m) && statusSays(m, text))
      return true;
  }
  return false;
}

// Re-reads the growing log until `done` says so or the timeout passes.
template <class Done>
int waitFor(const Options& o, Done done, const std::string& what) {
  const auto until =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(o.wait_timeout_s);
  while (std::chrono::steady_clock::now() < until) {
    if (done()) return 0;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  std::cout << "FAIL: " << what << " within " << o.wait_timeout_s << " s\n";
  return 1;
}

int waitForDistance(const Options& o) {
  const std::string what = "the vehicle did not fly " + std::to_string(o.wait_distance_m) + " m";
  return waitFor(
      o,
      [&] {
        const double d = distanceFlown(o.log);
        if (d < o.wait_distance_m) return false;
        std::cout << "flown " << d << " m\n";
        return true;
      },
      what);
}

int waitForStatus(const Options& o) {
  return waitFor(
      o,
      [&] {
        if (!statusSeen(o.log, o.wait_status)) return false;
        std::cout << "ARBITER_STATUS says \"" << o.wait_status << "\"\n";
        return true;
      },
      "no ARBITER_STATUS said \"" + o.wait_status + "\"");
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--expect-status" && i + 1 < argc) {
      o.statuses.push_back(argv[++i]);
    } else if (a == "--expect-counter" && i + 1 < argc) {
      o.counters.push_back(argv[++i]);
    } else if (a == "--stale-odometry-s" && i + 1 < argc) {
      o.stale_odometry_s = std::atof(argv[++i]);
    } else if (a == "--wait-distance" && i + 1 < argc) {
      o.wait_distance_m = std::atof(argv[++i]);
    } else if (a == "--wait-status" && i + 1 < argc) {
      o.wait_status = argv[++i];
    } else if (a == "--timeout" && i + 1 < argc) {
      o.wait_timeout_s = std::atof(argv[++i]);
    } else if (!a.empty() && a[0] != '-' && o.log.empty()) {
      o.log = a;
    } else {
      return usage();
    }
  }
  if (o.log.empty()) return usage();
  if (o.wait_distance_m >= 0.0) return waitForDistance(o);
  if (!o.wait_status.empty()) return waitForStatus(o);
  lcm::LogFile log(o.log, "r");
  if (!log.good()) {
    std::cerr << "mmh-fault-log-check: cannot read " << o.log << "\n";
    return 2;
  }

  // What the vehicle holds: sent trajectories by start time. As on the vehicle, a new one replaces
  // those that would start at or after its own start and takes over from the one before.
  struct Sent {
    mmh::Trajectory trajectory;
    int64_t start_utime = 0, id = 0;
  };
  std::vector<Sent> sent;
  constexpr size_t kSentKept = 16;
  int trajectories = 0, jumps = 0, stale_commits = 0, stops = 0;
  double max_jump_m = 0.0;
  int64_t last_odometry_utime = -1;
  std::optional<mmh::mission_status_t> mission;
  std::vector<bool> status_seen(o.statuses.size(), false);
  std::map<std::string, int64_t> counter_max;  // "service:name" -> largest value seen
  int64_t sim_jumps = 0, sim_late = 0, sim_lost = 0, sim_jumps_after_loss = 0;
  int by_mode[5] = {0, 0, 0, 0, 0};

  while (const lcm::LogEvent* e = log.readNextEvent()) {
    const std::string& ch = e->channel;
    if (endsWith(ch, "ODOMETRY")) {
      mmh::odometry_t m;
      if (decode(*e, &m)) last_odometry_utime = std::max(last_odometry_utime, m.header.utime);
    } else if (endsWith(ch, "TRAJECTORY")) {
      mmh::trajectory_t m;
      if (!decode(*e, &m) || m.num_pieces == 0) continue;
      ++trajectories;
      if (m.source_mode >= 0 && m.source_mode <= mmh::plan_request_t::MODE_STOP)
        ++by_mode[m.source_mode];
      if (m.source_mode == mmh::plan_request_t::MODE_STOP) ++stops;
      const bool from_mode = m.source_mode >= mmh::plan_request_t::MODE_FPM &&
                             m.source_mode <= mmh::plan_request_t::MODE_EAM;
      if (from_mode && last_odometry_utime >= 0 &&
          (m.header.utime - last_odometry_utime) * 1e-6 > o.stale_odometry_s) {
        ++stale_commits;
        std::cout << "STALE COMMIT: trajectory " << m.trajectory_id << " (mode "
                  << int(m.source_mode) << ") committed "
                  << (m.header.utime - last_odometry_utime) * 1e-6
                  << " s after the last ODOMETRY\n";
      }
      const mmh::Trajectory t = mmh::fromMsg(m);
      const bool first = sent.empty();
      while (!sent.empty() && sent.back().start_utime >= m.start_utime) sent.pop_back();
      if (!first && sent.empty()) {
        ++jumps;
        std::cout << "JUMP: trajectory " << m.trajectory_id << " (mode " << int(m.source_mode)
                  << ") starts before every trajectory sent before it\n";
      } else if (!first) {
        const Sent& previous = sent.back();
        const double dt = (m.start_utime - previous.start_utime) * 1e-6;
        const mmh::KinematicState a = previous.trajectory.state(dt);
        const mmh::KinematicState b = t.state(0.0);
        const double dp = (a.position - b.position).norm();
        const double dv = (a.velocity - b.velocity).norm();
        max_jump_m = std::max(max_jump_m, dp);
        if (dp > o.jump_position_m || dv > o.jump_velocity_mps) {
          ++jumps;
          std::cout << "JUMP: trajectory " << m.trajectory_id << " (mode " << int(m.source_mode)
                    << ") takes over " << previous.id << " at +" << dt << " s with " << dp << " m, "
                    << dv << " m/s difference\n";
        }
      }
      sent.push_back(Sent{t, m.start_utime, m.trajectory_id});
      if (sent.size() > kSentKept) sent.erase(sent.begin());
    } else if (endsWith(ch, "ARBITER_STATUS")) {
      mmh::arbiter_status_t m;
      if (!decode(*e, &m)) continue;
      for (size_t i = 0; i < o.statuses.size(); ++i) {
        if (statusSays(m, o.statuses[i])) status_seen[i] = true;
      }
    } else if (endsWith(ch, "MISSION_STATUS")) {
      mmh::mission_status_t m;
      if (decode(*e, &m)) mission = m;
    } else if (endsWith(ch, "HEARTBEAT")) {
      mmh::heartbeat_t m;
      if (!decode(*e, &m)) continue;
      for (size_t i = 0; i < m.counter_names.size() && i < m.counter_values.size(); ++i) {
        int64_t& v = counter_max[m.service + ":" + m.counter_names[i]];
        v = std::max(v, m.counter_values[i]);
        if (m.service == "mmh-sim" && m.counter_names[i] == "trajectory_jumps")
          sim_jumps = std::max(sim_jumps, m.counter_values[i]);
        if (m.service == "mmh-sim" && m.counter_names[i] == "trajectories_late")
          sim_late = std::max(sim_late, m.counter_values[i]);
        if (m.service == "mmh-sim" && m.counter_names[i] == "trajectories_lost")
          sim_lost = std::max(sim_lost, m.counter_values[i]);
        if (m.service == "mmh-sim" && m.counter_names[i] == "trajectory_jumps_after_loss")
          sim_jumps_after_loss = std::max(sim_jumps_after_loss, m.counter_values[i]);
      }
    }
  }

  bool ok = true;
  std::cout << "trajectories committed: " << trajectories << " (FPM " << by_mode[1] << ", SOM "
            << by_mode[2] << ", EAM " << by_mode[3] << ", stops " << stops
            << "), largest take-over gap " << max_jump_m << " m, jumps " << jumps
            << ", jumps seen by mmh-sim " << sim_jumps
            << "; delivered to mmh-sim after their start time " << sim_late << ", lost on the way "
            << sim_lost << " (steps onto the next one " << sim_jumps_after_loss << ")\n";
  if (trajectories == 0) {
    std::cout << "FAIL: no TRAJECTORY in the log\n";
    ok = false;
  }
  if (jumps > 0 || sim_jumps > 0) {
    std::cout << "FAIL: a committed trajectory jumped\n";
    ok = false;
  }
  if (stale_commits > 0) {
    std::cout << "FAIL: " << stale_commits << " mode trajectories committed on stale ODOMETRY\n";
    ok = false;
  }
  if (!mission || !mission->reached || mission->collided) {
    std::cout << "FAIL: mission "
              << (!mission            ? "status missing"
                  : mission->collided ? "collided"
                                      : "not reached")
              << "\n";
    ok = false;
  } else {
    std::cout << "mission: reached, flight time " << mission->flight_time_s << " s, "
              << mission->distance_m << " m\n";
  }
  for (size_t i = 0; i < o.statuses.size(); ++i) {
    std::cout << (status_seen[i] ? "" : "FAIL: ") << "ARBITER_STATUS \"" << o.statuses[i]
              << "\": " << (status_seen[i] ? "seen" : "never seen") << "\n";
    ok = ok && status_seen[i];
  }
  for (const std::string& c : o.counters) {
    const int64_t v = counter_max.count(c) ? counter_max[c] : 0;
    std::cout << (v > 0 ? "" : "FAIL: ") << "HEARTBEAT " << c << " = " << v << "\n";
    ok = ok && v > 0;
  }
  std::cout << (ok ? "log check PASS" : "log check FAIL") << "\n";
  return ok ? 0 : 1;
}
