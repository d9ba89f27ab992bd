// mmh-mission-report: waits for a running mission to end (MISSION_STATUS reached or collided, or a
// timeout) and prints what the demo and users want to know: flight time, distance, energy,
// planning iterations per mode and computational cost per iteration; for a mission of several
// waypoints every arrival, and for a vehicle that flies SETPOINT (mmh-sim --follow setpoint) the
// tracking error.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <vector>

#include "mmh/arbiter_status_t.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/node_options.hpp"
#include "mmh/mission_status_t.hpp"
#include "mmh/plan_result_t.hpp"

namespace {

struct Watcher {
  void onMission(const mmh::mission_status_t& m) {
    mission = m;
    have_mission = true;
  }
  void onResult(const mmh::plan_result_t& r) {
    if (r.mode < 1 || r.mode > 3) return;
    ++calls[r.mode];
    if (r.status != mmh::plan_result_t::STATUS_OK) ++failed[r.mode];
    compute_ms.push_back(r.compute_us * 1e-3);
  }
  void onStatus(const mmh::arbiter_status_t& s) {
    ++decisions;
    if (s.outcome == mmh::arbiter_status_t::OUTCOME_STOPPING) ++stops;
  }
  mmh::mission_status_t mission{};
  bool have_mission = false;
  int calls[4] = {0, 0, 0, 0}, failed[4] = {0, 0, 0, 0};
  int decisions = 0, stops = 0;
  std::vector<double> compute_ms;
};

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * (v.size() - 1) + 0.5)];
}

}  // namespace

int main(int argc, char** argv) {
  mmh::NodeOptions node;
  double timeout_s = 90.0;
  mmh::ArgParser parser("mmh-mission-report",
                        "Waits until the mission reaches its goal or collides (or --timeout), then "
                        "prints flight time, distance, energy, iterations per mode and cost per "
                        "iteration. Exit code 0 when the goal was reached without collision.");
  parser.addString("--lcm-url", &node.lcm_url, "LCM URL (default: $LCM_DEFAULT_URL or LCM's)");
  parser.addString("--prefix", &node.prefix, "vehicle channel prefix");
  parser.addDouble("--timeout", &timeout_s, "give up after this many seconds (wall clock)");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  mmh::setLogServiceName("mmh-mission-report");
  try {
    auto lcm = mmh::openLcm(node.lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-mission-report", node.prefix);
    Watcher w;
    ctx.subscribe(mmh::channels::kMissionStatus, &Watcher::onMission, &w);
    ctx.subscribe(mmh::channels::kPlanResult, &Watcher::onResult, &w);
    ctx.subscribe(mmh::channels::kArbiterStatus, &Watcher::onStatus, &w);
    mmh::installStopHandlers();
    const int64_t deadline = mmh::wallTimeUs() + static_cast<int64_t>(timeout_s * 1e6);
    while (!mmh::stopRequested() && mmh::wallTimeUs() < deadline &&
           !(w.have_mission && (w.mission.reached || w.mission.collided))) {
      lcm->handleTimeout(100);
    }
    const bool ok = w.have_mission && w.mission.reached && !w.mission.collided;
    const int total = w.calls[1] + w.calls[2] + w.calls[3];
    double sum = 0;
    for (double c : w.compute_ms) sum += c;
    std::printf("mission:        %s\n", !w.have_mission      ? "no MISSION_STATUS received"
                                        : w.mission.collided ? "COLLIDED"
                                        : w.mission.reached  ? "goal reached"
                                                             : "not reached (timeout)");
    if (w.have_mission) {
      std::printf("flight time:    %.2f s\n", w.mission.flight_time_s);
      std::printf("distance:       %.2f m\n", w.mission.distance_m);
      std::printf("energy:         %.2f m^2/s^5\n", w.mission.energy);
      if (w.mission.num_waypoints > 1) {
        std::printf("waypoints:      %d of %d reached\n", w.mission.num_arrivals,
                    w.mission.num_waypoints);
        for (int i = 0; i < w.mission.num_arrivals; ++i) {
          std::printf("  waypoint %d:    at %.2f s, %.2f m/s\n", w.mission.arrival_waypoint[i] + 1,
                      w.mission.arrival_time_s[i], w.mission.arrival_speed_mps[i]);
        }
      }
      if (w.mission.follows_setpoints) {
        std::printf(
            "tracking error: rms %.3f m, max %.3f m (SETPOINT through the tracking model)\n",
            w.mission.tracking_error_rms_m, w.mission.tracking_error_max_m);
      }
    }
    std::printf("iterations:     %d  (FPM %d, SOM %d, EAM %d; failed %d)\n", total, w.calls[1],
                w.calls[2], w.calls[3], w.failed[1] + w.failed[2] + w.failed[3]);
    std::printf("cost/iteration: mean %.3f ms, p50 %.3f ms, p99 %.3f ms\n",
                total ? sum / total : 0.0, percentile(w.compute_ms, 0.5),
                percentile(w.compute_ms, 0.99));
    std::printf("decisions:      %d (stopping trajectories: %d)\n", w.decisions, w.stops);
    return ok ? 0 : 3;
  } catch (const std::exception& e) {
    std::cerr << "mmh-mission-report: " << e.what() << "\n";
    return 1;
  }
}
