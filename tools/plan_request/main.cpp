// mmh-plan-request: asks one planning mode (FPM, SOM or EAM) for a trajectory over LCM, waits for
// its PLAN_RESULT and checks it independently: request id and mode, start state, target at rest,
// speed and acceleration limits (exact maxima), and - for the obstacle-avoiding modes - no
// collision with the map it published. Exit code 0 when the answer is what --expect asks for.
#include <chrono>
#include <cmath>
#include <iostream>
#include <sstream>
#include <thread>

#include "mmh/common/collision_check.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/common/node_options.hpp"
#include "mmh/common/vehicle_limits.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/plan_result_t.hpp"
#include "scene.hpp"

namespace {

struct Waiter {
  void onResult(const mmh::plan_result_t& m) {
    if (m.request_id == request_id && !got) {
      got = true;
      result = m;
    }
  }
  int64_t request_id = 0;
  bool got = false;
  mmh::plan_result_t result;
};

bool parsePoints(const std::string& text, std::vector<Eigen::Vector3d>* out) {
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ';')) {
    if (item.empty()) continue;
    Eigen::Vector3d v;
    if (!mmh::parseVector3(item, &v)) return false;
    out->push_back(v);
  }
  return true;
}

std::string vec(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s.precision(3);
  s << std::fixed << v.x() << "," << v.y() << "," << v.z();
  return s.str();
}

}  // namespace

int main(int argc, char** argv) {
  mmh::NodeOptions node;
  mmh::tools::SceneOptions scene;
  std::string mode_name = "fpm", waypoints_text, expect = "ok";
  Eigen::Vector3d start(0.0, 0.0, 1.2), velocity = Eigen::Vector3d::Zero(),
                                        acceleration = Eigen::Vector3d::Zero(),
                                        target(10.0, 0.0, 1.2), goal(std::nan(""), 0.0, 0.0);
  int expect_reason = -1;
  double timeout_s = 5.0, retry_s = 0.5;
  bool quiet = false;
  mmh::ArgParser parser("mmh-plan-request",
                        "Sends one PLAN_REQUEST_<MODE>, waits for the PLAN_RESULT and checks it.");
  mmh::addNodeOptions(parser, &node);
  parser.addString("--mode", &mode_name, "planning mode: fpm, som or eam");
  parser.addVector3("--start", &start, "start position x,y,z (m)");
  parser.addVector3("--velocity", &velocity, "start velocity x,y,z (m/s)");
  parser.addVector3("--acceleration", &acceleration, "start acceleration x,y,z (m/s^2)");
  parser.addVector3("--target", &target, "local target x,y,z (m), reached at rest");
  parser.addVector3("--goal", &goal, "mission goal x,y,z (default: the target)");
  parser.addString("--waypoints", &waypoints_text, "intermediate waypoints \"x,y,z;x,y,z\"");
  parser.addString("--expect", &expect, "ok, failed or any: the status that counts as success");
  parser.addInt("--expect-reason", &expect_reason, "with --expect failed: the reason code");
  parser.addDouble("--timeout", &timeout_s, "give up after this many seconds");
  parser.addDouble("--retry-period", &retry_s, "resend the request this often until answered");
  parser.addFlag("--quiet", &quiet, "print only failures");
  mmh::tools::addSceneOptions(parser, &scene);
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  int8_t mode = 0;
  if (mode_name == "fpm") mode = mmh::plan_request_t::MODE_FPM;
  if (mode_name == "som") mode = mmh::plan_request_t::MODE_SOM;
  if (mode_name == "eam") mode = mmh::plan_request_t::MODE_EAM;
  if (mode == 0 || (expect != "ok" && expect != "failed" && expect != "any")) {
    std::cerr
        << "mmh-plan-request: --mode must be fpm, som or eam and --expect ok, failed or any\n";
    return 2;
  }
  std::vector<Eigen::Vector3d> waypoints;
  if (!parsePoints(waypoints_text, &waypoints)) {
    std::cerr << "mmh-plan-request: bad --waypoints '" << waypoints_text << "'\n";
    return 2;
  }
  if (std::isnan(goal.x())) goal = target;
  mmh::setLogServiceName("mmh-plan-request");
  try {
    const mmh::Config config = mmh::loadNodeConfig(node);
    const mmh::VehicleLimits limits = mmh::loadVehicleLimits(config);
    const double v_max = limits.max_vel_mps;
    const double a_max = limits.max_acc_mps2;
    auto lcm = mmh::openLcm(node.lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-plan-request", node.prefix);
    Waiter waiter;
    ctx.subscribe(mmh::channels::kPlanResult, &Waiter::onResult, &waiter);

    // The map: SOM and EAM need one; FPM only gets one if a scene was asked for.
    const bool scene_given = !scene.pillars.empty() || scene.forest_density > 0.0;
    const bool send_map = !scene.no_map && (mode != mmh::plan_request_t::MODE_FPM || scene_given);
    std::unique_ptr<mmh::VoxelGrid> grid;
    if (send_map) grid = mmh::tools::buildScene(scene, config, start);

    const int64_t now = mmh::wallTimeUs();
    mmh::plan_request_t req{};
    req.request_id = now;  // unique across runs
    req.mode = mode;
    req.start_utime = now + 100'000;
    mmh::setStartState(mmh::KinematicState{start, velocity, acceleration}, req);
    mmh::fromVec3(target, req.target);
    mmh::fromVec3(goal, req.goal);
    req.deadline_utime = now + static_cast<int64_t>(timeout_s * 1e6);
    mmh::setWaypoints(waypoints, req);
    waiter.request_id = req.request_id;
    const std::string channel =
        mode == mmh::plan_request_t::MODE_FPM   ? mmh::channels::kPlanRequestFpm
        : mode == mmh::plan_request_t::MODE_SOM ? mmh::channels::kPlanRequestSom
                                                : mmh::channels::kPlanRequestEam;
    mmh::installStopHandlers();
    const int64_t deadline = now + static_cast<int64_t>(timeout_s * 1e6);
    int64_t next_send = now;
    int sent = 0;
    while (!waiter.got && mmh::wallTimeUs() < deadline && !mmh::stopRequested()) {
      if (mmh::wallTimeUs() >= next_send) {
        // Until an answer comes (the service may still be starting), send again: a fresh map
        // keyframe first, then the same request.
        if (grid) {
          mmh::local_map_t map = mmh::makeKeyframe(*grid, mmh::wallTimeUs() / 1000);
          map.header.utime = mmh::wallTimeUs();
          req.map_seq = map.map_seq;
          ctx.publish(mmh::channels::kLocalMap, map);
        }
        req.header.utime = mmh::wallTimeUs();
        ctx.publish(channel, req);
        ++sent;
        next_send = mmh::wallTimeUs() + static_cast<int64_t>(retry_s * 1e6);
      }
      lcm->handleTimeout(20);
    }
    if (!waiter.got) {
      std::cerr << "mmh-plan-request: no PLAN_RESULT for request " << req.request_id << " on "
                << ctx.channel(mmh::channels::kPlanResult) << " within " << timeout_s << " s ("
                << sent << " requests sent on " << ctx.channel(channel) << ")\n";
      return 1;
    }

    const mmh::plan_result_t& r = waiter.result;
    std::vector<std::string> problems;
    if (r.mode != mode) problems.push_back("answer is for mode " + std::to_string(r.mode));
    const bool ok = r.status == mmh::plan_result_t::STATUS_OK;
    std::ostringstream report;
    report << "PLAN_RESULT request " << r.request_id << " mode " << mode_name << ": "
           << (ok ? "OK" : "FAILED") << " reason " << r.reason
           << (r.detail.empty() ? "" : " (" + r.detail + ")") << ", compute " << r.compute_us
           << " us\n";
    if (ok) {
      const mmh::Trajectory t = mmh::fromMsg(r.trajectory);
      const double T = t.duration();
      const double vm = t.maxSpeed(), am = t.maxAcceleration();
      report << "  trajectory: " << t.numPieces() << " pieces, " << T << " s, " << t.arcLength()
             << " m, max speed " << vm << " m/s, max acceleration " << am << " m/s^2, jerk energy "
             << t.jerkEnergy() << "\n"
             << "  cost: total " << r.cost_total << " = control " << r.cost_control << " + time "
             << r.cost_time << " + penalty " << r.cost_penalty << "\n"
             << "  start " << vec(t.position(0)) << " -> end " << vec(t.position(T)) << "\n";
      if (!t.isFinite() || t.empty()) problems.push_back("trajectory is empty or not finite");
      if (r.trajectory.start_utime != req.start_utime) problems.push_back("start_utime differs");
      if (r.trajectory.source_mode != mode) problems.push_back("source_mode differs");
      if ((t.position(0) - start).norm() > 1e-6 || (t.velocity(0) - velocity).norm() > 1e-6 ||
          (t.acceleration(0) - acceleration).norm() > 1e-6)
        problems.push_back("does not start at the start state");
      if ((t.position(T) - target).norm() > 1e-3 || t.velocity(T).norm() > 1e-3 ||
          t.acceleration(T).norm() > 1e-3)
        problems.push_back("does not end at the target at rest");
      if (vm > v_max + 1e-6) problems.push_back("speed limit broken: " + std::to_string(vm));
      if (am > a_max + 1e-6) problems.push_back("acceleration limit broken: " + std::to_string(am));
      for (const Eigen::Vector3d& w : waypoints) {
        double closest = 1e9;
        for (double s = 0.0; s <= T; s += 0.001)
          closest = std::min(closest, (t.position(s) - w).norm());
        if (closest > 1e-2) problems.push_back("misses waypoint " + vec(w));
      }
      if (grid) {
        const auto hit = mmh::firstCollisionTime(*grid, t, 0.0, T);
        if (hit) {
          report << "  collides with the map (inflated) at t = " << *hit << " s, "
                 << vec(t.position(*hit)) << "\n";
          if (mode != mmh::plan_request_t::MODE_FPM)  // FPM ignores obstacles by design
            problems.push_back("collides with the map");
        } else {
          report << "  free of the map's (inflated) obstacles\n";
        }
      }
    }
    if (expect == "ok" && !ok) problems.push_back("expected STATUS_OK");
    if (expect == "failed" && ok) problems.push_back("expected STATUS_FAILED");
    if (expect == "failed" && expect_reason >= 0 && r.reason != expect_reason)
      problems.push_back("expected reason " + std::to_string(expect_reason));
    for (const std::string& p : problems) report << "  PROBLEM: " << p << "\n";
    if (!quiet || !problems.empty()) std::cout << report.str();
    return problems.empty() ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "mmh-plan-request: " << e.what() << "\n";
    return 1;
  }
}
