// mmh-som-test-client: publishes the S-bend test world as a LOCAL_MAP keyframe and one
// PLAN_REQUEST_SOM (a moving start), waits for the PLAN_RESULT and checks it without any SOM
// code: status, contract fields, start state, end at the target at rest, exact speed and
// acceleration maxima, and fine sampling against the occupied voxels of the map it sent. A
// second request, whose target lies in an obstacle, must be refused with
// REASON_TARGET_IN_OBSTACLE. Exit 0 when every check passes.
#include <iostream>

#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/common/node_options.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/plan_result_t.hpp"
#include "som_test_worlds.hpp"

namespace {

struct Sink {
  void on(const mmh::plan_result_t& r) { results.push_back(r); }
  std::vector<mmh::plan_result_t> results;
};

mmh::plan_request_t makeRequest(int64_t id, int64_t utime, const mmh::KinematicState& start,
                                const Eigen::Vector3d& target) {
  mmh::plan_request_t r{};
  r.header.utime = utime;
  r.request_id = id;
  r.mode = mmh::plan_request_t::MODE_SOM;
  r.start_utime = utime + 50'000;
  mmh::setStartState(start, r);
  mmh::fromVec3(target, r.target);
  mmh::fromVec3(target, r.goal);
  r.deadline_utime = utime + 1'000'000;
  r.map_seq = 1;
  return r;
}

int failures = 0;
void check(bool ok, const std::string& what) {
  std::cout << (ok ? "ok    " : "FAIL  ") << what << "\n";
  if (!ok) ++failures;
}

}  // namespace

int main(int argc, char** argv) {
  mmh::NodeOptions node;
  double timeout_s = 30.0;
  mmh::ArgParser parser("mmh-som-test-client", "Checks a running mmh-som end to end.");
  mmh::addNodeOptions(parser, &node);
  parser.addDouble("--timeout", &timeout_s, "give up after this many seconds");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  mmh::setLogServiceName("mmh-som-test-client");
  try {
    auto lcm = mmh::openLcm(node.lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-som-test-client", node.prefix);
    Sink sink;
    ctx.subscribe(mmh::channels::kPlanResult, &Sink::on, &sink);
    const som_test::World world = som_test::sBend();
    mmh::KinematicState start;
    start.position = world.start;
    start.velocity = Eigen::Vector3d(1.5, 0.5, 0.0);
    start.acceleration = Eigen::Vector3d(0.2, 0.0, 0.0);

    // Until both answers are in: the map, then the two requests (mmh-som may still be starting,
    // so everything is sent again every 0.5 s with a later time stamp).
    const int64_t deadline = mmh::wallTimeUs() + static_cast<int64_t>(timeout_s * 1e6);
    int64_t utime = 1'000'000, last_send = 0;
    auto answered = [&](int64_t id) {
      for (const auto& r : sink.results)
        if (r.request_id == id) return &r;
      return static_cast<const mmh::plan_result_t*>(nullptr);
    };
    while ((!answered(1) || !answered(2)) && mmh::wallTimeUs() < deadline) {
      if (mmh::wallTimeUs() - last_send > 500'000) {
        last_send = mmh::wallTimeUs();
        mmh::local_map_t map = mmh::makeKeyframe(*world.grid, 1);
        map.header.utime = utime;
        ctx.publish(mmh::channels::kLocalMap, map);
        lcm->handleTimeout(100);
        auto ok_req = makeRequest(1, utime + 10, start, world.target);
        ctx.publish(mmh::channels::kPlanRequestSom, ok_req);
        mmh::KinematicState rest;
        rest.position = world.start;
        auto bad_req = makeRequest(2, utime + 20, rest, Eigen::Vector3d(4.0, -2.0, 1.2));
        ctx.publish(mmh::channels::kPlanRequestSom, bad_req);
        utime += 1'000'000;
      }
      lcm->handleTimeout(50);
    }
    const mmh::plan_result_t* r = answered(1);
    check(r != nullptr, "PLAN_RESULT for request 1 received");
    if (r) {
      check(r->status == mmh::plan_result_t::STATUS_OK, "status OK (" + r->detail + ")");
      check(r->mode == mmh::plan_request_t::MODE_SOM, "mode SOM");
      check(r->header.source == "mmh-som", "source mmh-som");
      check(r->map_seq == 1, "map_seq 1");
      check(r->compute_us > 0, "compute_us " + std::to_string(r->compute_us));
      check(r->trajectory.source_mode == mmh::plan_request_t::MODE_SOM, "trajectory source_mode");
      // Requests go out at utime k * 1e6 + 10 with start_utime 50 ms later.
      check(r->trajectory.start_utime % 1'000'000 == 50'010,
            "trajectory start_utime = request start_utime");
      const mmh::Trajectory t = mmh::fromMsg(r->trajectory);
      check(!t.empty() && t.isFinite(), "finite trajectory");
      if (!t.empty()) {
        check(t.position(0) == start.position && t.velocity(0) == start.velocity &&
                  t.acceleration(0) == start.acceleration,
              "starts exactly at the request's state");
        const double T = t.duration();
        check((t.position(T) - world.target).norm() < 1e-3 && t.velocity(T).norm() < 1e-3 &&
                  t.acceleration(T).norm() < 1e-3,
              "ends at the target at rest");
        check(t.maxSpeed() <= 3.0 * 1.01, "max speed " + std::to_string(t.maxSpeed()));
        check(t.maxAcceleration() <= 2.0 * 1.01,
              "max acceleration " + std::to_string(t.maxAcceleration()));
        bool free = true;
        for (double s = 0.0; s <= T; s += 0.002)
          free = free && !world.grid->isOccupiedPoint(t.position(s));
        check(free, "no sample in an occupied voxel (flight time " + std::to_string(T) + " s)");
      }
    }
    const mmh::plan_result_t* bad = answered(2);
    check(bad != nullptr, "PLAN_RESULT for request 2 received");
    if (bad) {
      check(bad->status == mmh::plan_result_t::STATUS_FAILED &&
                bad->reason == mmh::plan_result_t::REASON_TARGET_IN_OBSTACLE,
            "target in an obstacle refused with REASON_TARGET_IN_OBSTACLE (" + bad->detail + ")");
    }
    return failures == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "mmh-som-test-client: " << e.what() << "\n";
    return 1;
  }
}
