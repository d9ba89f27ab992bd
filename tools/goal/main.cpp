// mmh-goal: publishes the mission goal (GOAL, goal_t), repeated at a low rate so that services
// started later still get it. The same --id means the same goal; a new id is a goal change.
// Stamped with the wall clock, which is the message clock of real-time runs (mmh-sim --realtime).
#include <chrono>
#include <iostream>
#include <limits>
#include <thread>

#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/common/node_options.hpp"
#include "mmh/goal_t.hpp"

int main(int argc, char** argv) {
  mmh::NodeOptions node;
  Eigen::Vector3d goal = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  int id = 1, count = 0;
  double rate_hz = 1.0;
  mmh::ArgParser parser("mmh-goal", "Publishes the mission goal on GOAL, repeatedly.");
  mmh::addNodeOptions(parser, &node);
  parser.addVector3("--goal", &goal, "goal position x,y,z (m, world frame), required");
  parser.addInt("--id", &id, "goal id (same id = same goal)");
  parser.addDouble("--rate-hz", &rate_hz, "messages per second");
  parser.addInt("--count", &count, "messages to send (0: until Ctrl-C)");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  if (!goal.allFinite()) {
    std::cerr << "mmh-goal: --goal x,y,z is required\n" << parser.usage();
    return 2;
  }
  if (!(rate_hz > 0.0 && rate_hz <= 100.0) || count < 0 || id < 1) {
    std::cerr << "mmh-goal: --rate-hz must be in (0, 100], --count >= 0, --id >= 1\n";
    return 2;
  }
  mmh::setLogServiceName("mmh-goal");
  try {
    auto lcm = mmh::openLcm(node.lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-goal", node.prefix);
    mmh::installStopHandlers();
    const auto period = std::chrono::duration<double>(1.0 / rate_hz);
    int sent = 0;
    while (!mmh::stopRequested() && (count == 0 || sent < count)) {
      mmh::goal_t msg{};
      msg.header.utime = mmh::wallTimeUs();
      msg.goal_id = id;
      mmh::fromVec3(goal, msg.position);
      ctx.publish(mmh::channels::kGoal, msg);
      ++sent;
      if (count != 0 && sent >= count) break;
      std::this_thread::sleep_for(period);
    }
    std::cout << "mmh-goal: sent " << sent << " GOAL messages (id " << id << ") on "
              << ctx.channel(mmh::channels::kGoal) << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "mmh-goal: " << e.what() << "\n";
    return 1;
  }
}
