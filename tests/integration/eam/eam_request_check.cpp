// mmh-eam-request-check: drives a running mmh-eam over LCM for the integration test. Publishes
// LOCAL_MAP keyframes and PLAN_REQUEST_EAM messages and checks every PLAN_RESULT independently
// (start state, end at rest, collision against the map, limits). Exit 0 when all checks pass.
#include <iostream>
#include <optional>
#include <string>

#include "eam_test_grids.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/common/node_options.hpp"
#include "mmh/heartbeat_t.hpp"
#include "mmh/plan_result_t.hpp"

using Eigen::Vector3d;

namespace {

struct Listener {
  void onResult(const mmh::plan_result_t& m) { results.push_back(m); }
  void onHeartbeat(const mmh::heartbeat_t& m) {
    if (m.service == "mmh-eam") eam_alive = true;
  }
  std::vector<mmh::plan_result_t> results;
  bool eam_alive = false;
};

int failures = 0;
void check(bool ok, const std::string& what) {
  std::cout << (ok ? "  ok   " : "  FAIL ") << what << "\n";
  if (!ok) ++failures;
}

// Handles LCM until pred() or the timeout (wall clock: this is a test driver, not a node).
template <class Pred>
bool waitFor(lcm::LCM& lcm, double timeout_s, Pred pred) {
  const int64_t deadline = mmh::wallTimeUs() + static_cast<int64_t>(timeout_s * 1e6);
  while (!pred() && mmh::wallTimeUs() < deadline) lcm.handleTimeout(50);
  return pred();
}

std::optional<mmh::plan_result_t> request(lcm::LCM& lcm, mmh::ServiceContext& ctx, Listener& l,
                                          int64_t id, const Vector3d& start, const Vector3d& target,
                                          int64_t utime) {
  mmh::plan_request_t req{};
  req.header.utime = utime;
  req.request_id = id;
  req.mode = mmh::plan_request_t::MODE_EAM;
  req.start_utime = utime;
  mmh::KinematicState s;
  s.position = start;
  mmh::setStartState(s, req);
  mmh::fromVec3(target, req.target);
  mmh::fromVec3(target, req.goal);
  req.deadline_utime = utime + 1'000'000;
  // The committed trajectory: straight at up to ~2.7 m/s, started with this request.
  const mmh::Trajectory committed = eam_test::straightLine(start, target, 7.0);
  req.reference.start_utime = utime;
  req.reference.trajectory_id = 100 + id;
  req.reference.source_mode = mmh::plan_request_t::MODE_FPM;
  mmh::toMsg(committed, req.reference);
  ctx.publish(mmh::channels::kPlanRequestEam, req);
  const size_t before = l.results.size();
  if (!waitFor(lcm, 10.0, [&] { return l.results.size() > before; })) return std::nullopt;
  for (const auto& r : l.results)
    if (r.request_id == id) return r;
  return std::nullopt;
}

void checkTrajectory(const mmh::plan_result_t& res, const mmh::VoxelGrid& grid,
                     const Vector3d& start, const Vector3d& target, int64_t start_utime) {
  const mmh::Trajectory t = mmh::fromMsg(res.trajectory);
  check(res.trajectory.start_utime == start_utime, "trajectory starts at request.start_utime");
  check(res.trajectory.source_mode == mmh::plan_request_t::MODE_EAM, "source_mode is EAM");
  check(!t.empty() && (t.position(0.0) - start).norm() < 1e-9 && t.velocity(0.0).norm() < 1e-9 &&
            t.acceleration(0.0).norm() < 1e-8,
        "starts at the request state");
  check(!t.empty() && (t.position(t.duration()) - target).norm() < 1e-9 &&
            t.velocity(t.duration()).norm() < 1e-9,
        "ends at the target at rest");
  check(eam_test::firstBlockedTime(grid, t, false) < 0.0, "collision-free on the inflated map");
  check(t.maxSpeed() <= 3.0 * 1.05 && t.maxAcceleration() <= 2.0 * 1.05,
        "within 5% of v_max and a_max");
}

}  // namespace

int main(int argc, char** argv) {
  mmh::NodeOptions node;
  mmh::ArgParser parser("mmh-eam-request-check", "Integration check of a running mmh-eam.");
  mmh::addNodeOptions(parser, &node);
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  try {
    auto lcm = mmh::openLcm(node.lcm_url);
    mmh::ServiceContext ctx(*lcm, "eam-check", node.prefix);
    Listener l;
    ctx.subscribe(mmh::channels::kPlanResult, &Listener::onResult, &l);
    ctx.subscribe(mmh::channels::kHeartbeat, &Listener::onHeartbeat, &l);
    check(waitFor(*lcm, 15.0, [&] { return l.eam_alive; }), "mmh-eam heartbeat received");
    if (!l.eam_alive) return 1;

    const Vector3d start(0, 0, 1.2), target(10, 0, 1.2);
    // 1. A pillar across the committed trajectory.
    mmh::VoxelGrid pillar = eam_test::freeGrid();
    eam_test::addPillar(pillar, 5.0, 0.05, 0.5);
    auto map1 = mmh::makeKeyframe(pillar, 1);
    map1.header.utime = 1'000'000;
    ctx.publish(mmh::channels::kLocalMap, map1);
    auto r1 = request(*lcm, ctx, l, 1, start, target, 1'100'000);
    check(r1.has_value(), "answer to request 1 (pillar)");
    if (r1) {
      check(r1->status == mmh::plan_result_t::STATUS_OK, "request 1 succeeded: " + r1->detail);
      check(r1->map_seq == 1 && !r1->narrow && r1->compute_us > 0, "map_seq 1, open weights");
      std::cout << "  request 1: " << r1->compute_us << " us, cost " << r1->cost_total << "\n";
      if (r1->status == mmh::plan_result_t::STATUS_OK)
        checkTrajectory(*r1, pillar, start, target, 1'100'000);
    }
    // 2. The target inside the pillar: a reason code, not silence.
    auto r2 = request(*lcm, ctx, l, 2, start, Vector3d(5.0, 0.0, 1.2), 1'200'000);
    check(r2 && r2->status == mmh::plan_result_t::STATUS_FAILED &&
              r2->reason == mmh::plan_result_t::REASON_TARGET_IN_OBSTACLE,
          "request 2 (target in obstacle) fails with REASON_TARGET_IN_OBSTACLE");
    // 3. A wall with a narrow opening: the narrow weights, observable in the result.
    mmh::VoxelGrid wall = eam_test::freeGrid();
    eam_test::addWallWithGap(wall, 5.0, 0.3, 1.0, 1.0);
    auto map2 = mmh::makeKeyframe(wall, 2);
    map2.header.utime = 1'300'000;
    ctx.publish(mmh::channels::kLocalMap, map2);
    auto r3 = request(*lcm, ctx, l, 3, start, target, 1'400'000);
    check(r3.has_value(), "answer to request 3 (narrow gap)");
    if (r3) {
      check(r3->status == mmh::plan_result_t::STATUS_OK, "request 3 succeeded: " + r3->detail);
      check(r3->narrow && r3->map_seq == 2, "narrow weights reported, map_seq 2");
      if (r3->status == mmh::plan_result_t::STATUS_OK)
        checkTrajectory(*r3, wall, start, target, 1'400'000);
    }
  } catch (const std::exception& e) {
    std::cerr << "mmh-eam-request-check: " << e.what() << "\n";
    return 1;
  }
  std::cout << (failures == 0 ? "all checks passed\n" : "checks failed\n");
  return failures == 0 ? 0 : 1;
}
