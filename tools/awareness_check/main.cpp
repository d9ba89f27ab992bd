// mmh-awareness-check: gives mmh-awareness a map (a synthetic LOCAL_MAP keyframe), a pose and a
// goal over LCM and prints the AWARENESS it answers. Exit code 0 when the answer is what
// --expect asks for.
#include <cmath>
#include <iostream>

#include "mmh/awareness_t.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/common/node_options.hpp"
#include "mmh/goal_t.hpp"
#include "mmh/odometry_t.hpp"
#include "scene.hpp"

namespace {

struct Waiter {
  void onAwareness(const mmh::awareness_t& m) {
    if (m.goal_id == goal_id && m.map_seq >= first_map_seq && !got) {
      got = true;
      answer = m;
    }
  }
  int64_t goal_id = 0, first_map_seq = 0;
  bool got = false;
  mmh::awareness_t answer;
};

}  // namespace

int main(int argc, char** argv) {
  mmh::NodeOptions node;
  mmh::tools::SceneOptions scene;
  Eigen::Vector3d position(0.0, 0.0, 1.2), goal(20.0, 0.0, 1.2);
  std::string expect = "any";
  double timeout_s = 5.0, retry_s = 0.5;
  mmh::ArgParser parser("mmh-awareness-check",
                        "Sends LOCAL_MAP (a synthetic scene), ODOMETRY and GOAL and prints the "
                        "AWARENESS answer.");
  mmh::addNodeOptions(parser, &node);
  parser.addVector3("--position", &position, "vehicle position x,y,z (m)");
  parser.addVector3("--goal", &goal, "goal x,y,z (m)");
  parser.addString("--expect", &expect, "clear, blocked, narrow or any");
  parser.addDouble("--timeout", &timeout_s, "give up after this many seconds");
  parser.addDouble("--retry-period", &retry_s, "resend until answered, this often (s)");
  mmh::tools::addSceneOptions(parser, &scene);
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  if (expect != "clear" && expect != "blocked" && expect != "narrow" && expect != "any") {
    std::cerr << "mmh-awareness-check: --expect must be clear, blocked, narrow or any\n";
    return 2;
  }
  mmh::setLogServiceName("mmh-awareness-check");
  try {
    const mmh::Config config = mmh::loadNodeConfig(node);
    auto lcm = mmh::openLcm(node.lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-awareness-check", node.prefix);
    Waiter waiter;
    ctx.subscribe(mmh::channels::kAwareness, &Waiter::onAwareness, &waiter);
    const auto grid = mmh::tools::buildScene(scene, config, position);
    const int64_t start = mmh::wallTimeUs();
    waiter.goal_id = start;  // unique across runs
    waiter.first_map_seq = start / 1000;
    mmh::installStopHandlers();
    const int64_t deadline = start + static_cast<int64_t>(timeout_s * 1e6);
    int64_t next_send = start;
    while (!waiter.got && mmh::wallTimeUs() < deadline && !mmh::stopRequested()) {
      if (mmh::wallTimeUs() >= next_send) {
        // Pose and goal first, then a new keyframe: the map update triggers the answer.
        mmh::odometry_t odom{};
        odom.header.utime = mmh::wallTimeUs();
        mmh::fromVec3(position, odom.position);
        odom.orientation[0] = 1.0;
        ctx.publish(mmh::channels::kOdometry, odom);
        mmh::goal_t g{};
        g.header.utime = mmh::wallTimeUs();
        g.goal_id = waiter.goal_id;
        mmh::fromVec3(goal, g.position);
        ctx.publish(mmh::channels::kGoal, g);
        if (!scene.no_map) {
          mmh::local_map_t map = mmh::makeKeyframe(*grid, mmh::wallTimeUs() / 1000);
          map.header.utime = mmh::wallTimeUs();
          ctx.publish(mmh::channels::kLocalMap, map);
        }
        next_send = mmh::wallTimeUs() + static_cast<int64_t>(retry_s * 1e6);
      }
      lcm->handleTimeout(20);
    }
    if (!waiter.got) {
      std::cerr << "mmh-awareness-check: no AWARENESS on " << ctx.channel(mmh::channels::kAwareness)
                << " within " << timeout_s << " s\n";
      return 1;
    }
    const mmh::awareness_t& a = waiter.answer;
    const char* names[] = {"clear", "blocked", "narrow"};
    const std::string reason = a.reason >= 0 && a.reason <= 2 ? names[a.reason] : "unknown";
    std::cout << "AWARENESS map_seq " << a.map_seq << " goal " << a.goal_id
              << ": S = " << (a.safe ? "true" : "false") << " (" << reason << "), ray end ("
              << a.ray_end[0] << ", " << a.ray_end[1] << ", " << a.ray_end[2] << ")";
    if (a.has_blocked_point)
      std::cout << ", first blocked (" << a.first_blocked[0] << ", " << a.first_blocked[1] << ", "
                << a.first_blocked[2] << ")";
    std::cout << ", " << a.compute_ns / 1000.0 << " us\n";
    if (expect != "any" && expect != reason) {
      std::cout << "  PROBLEM: expected " << expect << "\n";
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "mmh-awareness-check: " << e.what() << "\n";
    return 1;
  }
}
