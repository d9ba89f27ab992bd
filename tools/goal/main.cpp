// mmh-goal: publishes the mission goal (GOAL, goal_t), repeated at a low rate so that services
// started later still get it. The same --id means the same goal; a new id is a goal change.
// With --waypoints or --mission it flies a mission: it follows ODOMETRY and hands the next
// waypoint over as a new GOAL (id + index) when the vehicle reaches the current one
// (mmh/common/mission.hpp), and exits after the last. Stamped with the wall clock, which is the
// message clock of real-time runs (mmh-sim --realtime).
#include <chrono>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>

#include "mmh/common/geofence.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/mission.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/common/node_options.hpp"
#include "mmh/goal_t.hpp"
#include "mmh/odometry_t.hpp"

namespace {

// The mission's executor: ODOMETRY in, the current waypoint out.
struct MissionRunner {
  mmh::MissionSequencer sequencer;
  bool advanced = false;
  void onOdometry(const mmh::odometry_t& msg) {
    const int index = sequencer.index();
    if (!sequencer.update(mmh::toVec3(msg.position), mmh::toVec3(msg.velocity))) return;
    const mmh::Waypoint& w = sequencer.waypoints()[static_cast<size_t>(index)];
    std::cout << "mmh-goal: waypoint " << index + 1 << " of " << sequencer.size() << " ("
              << w.position.x() << ", " << w.position.y() << ", " << w.position.z()
              << ") reached at " << mmh::toVec3(msg.velocity).norm() << " m/s" << std::endl;
    advanced = true;
  }
};

mmh::goal_t goalMessage(int64_t id, const mmh::Waypoint& w, int index, int count) {
  mmh::goal_t msg{};
  msg.header.utime = mmh::wallTimeUs();
  msg.goal_id = id;
  mmh::fromVec3(w.position, msg.position);
  msg.waypoint_index = index;
  msg.num_waypoints = count;
  msg.tolerance_m = count > 0 ? w.tolerance_m : 0.0;
  msg.stop = w.stop;
  return msg;
}

}  // namespace

int main(int argc, char** argv) {
  mmh::NodeOptions node;
  Eigen::Vector3d goal = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  std::string waypoints_text, mission_path;
  int id = 1, count = 0;
  double rate_hz = 1.0;
  mmh::ArgParser parser("mmh-goal",
                        "Publishes the mission goal on GOAL, repeatedly; or flies a mission of "
                        "waypoints one after another.");
  mmh::addNodeOptions(parser, &node);
  parser.addVector3("--goal", &goal, "goal position x,y,z (m, world frame)");
  parser.addString("--waypoints", &waypoints_text,
                   "a mission: \"x,y,z;x,y,z;...\", passed at speed, stopping at the last");
  parser.addString("--mission", &mission_path,
                   "a mission file (YAML: waypoints with position, tolerance_m, stop; "
                   "docs/operations.md#missions)");
  parser.addInt("--id", &id, "goal id (same id = same goal; a mission's waypoint i has id + i)");
  parser.addDouble("--rate-hz", &rate_hz, "messages per second");
  parser.addInt("--count", &count, "messages to send (0: until Ctrl-C; a single goal only)");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  const int sources = goal.allFinite() + !waypoints_text.empty() + !mission_path.empty();
  if (sources != 1) {
    std::cerr << "mmh-goal: give one of --goal x,y,z, --waypoints or --mission\n" << parser.usage();
    return 2;
  }
  if (!(rate_hz > 0.0 && rate_hz <= 100.0) || count < 0 || id < 1) {
    std::cerr << "mmh-goal: --rate-hz must be in (0, 100], --count >= 0, --id >= 1\n";
    return 2;
  }
  mmh::setLogServiceName("mmh-goal");
  std::vector<mmh::Waypoint> waypoints;
  try {
    const mmh::Config config = mmh::loadNodeConfig(node);
    const mmh::MissionRules rules = mmh::loadMissionRules(config);
    if (!waypoints_text.empty()) waypoints = mmh::parseWaypointList(waypoints_text, rules);
    if (!mission_path.empty()) waypoints = mmh::loadMissionFile(mission_path, rules);
    // A goal outside the fence would be refused by the arbiter: say so now, naming the keys.
    const mmh::Geofence fence = mmh::loadGeofence(config);
    const std::string why = waypoints.empty() ? mmh::geofenceViolation(fence, goal, "the goal")
                                              : mmh::missionGeofenceViolation(waypoints, fence);
    if (!why.empty()) {
      std::cerr << "mmh-goal: " << why << "\n";
      return 2;
    }
  } catch (const mmh::MissionError& e) {
    std::cerr << "mmh-goal: " << e.what() << "\n";
    return 2;
  } catch (const mmh::ConfigError& e) {
    std::cerr << "mmh-goal: " << e.what() << "\n";
    return 1;
  }
  try {
    const mmh::Config config = mmh::loadNodeConfig(node);
    auto lcm = mmh::openLcm(node.lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-goal", node.prefix);
    mmh::installStopHandlers();
    std::unique_ptr<MissionRunner> mission;
    if (!waypoints.empty()) {
      mission = std::make_unique<MissionRunner>(MissionRunner{
          mmh::MissionSequencer(waypoints, mmh::loadMissionRules(config).stop_speed_mps)});
      ctx.subscribe(mmh::channels::kOdometry, &MissionRunner::onOdometry, mission.get());
    }
    const auto period_us = static_cast<int64_t>(1e6 / rate_hz);
    int sent = 0;
    int64_t next = mmh::wallTimeUs();
    while (!mmh::stopRequested()) {
      if (mission && mission->sequencer.finished()) break;
      const bool handover = mission && mission->advanced;
      if (handover || mmh::wallTimeUs() >= next) {
        mmh::goal_t msg =
            mission ? goalMessage(id + mission->sequencer.index(), mission->sequencer.current(),
                                  mission->sequencer.index(), mission->sequencer.size())
                    : goalMessage(id, mmh::Waypoint{goal, 0.0, true}, 0, 0);
        ctx.publish(mmh::channels::kGoal, msg);
        if (mission) mission->advanced = false;
        ++sent;
        next = mmh::wallTimeUs() + period_us;
        if (!mission && count != 0 && sent >= count) break;
      }
      const int64_t wait_ms = std::max<int64_t>(0, (next - mmh::wallTimeUs()) / 1000);
      if (lcm->handleTimeout(static_cast<int>(std::min<int64_t>(wait_ms, 100))) < 0 &&
          !mmh::stopRequested()) {
        std::cerr << "mmh-goal: LCM handle failed\n";
        return 1;
      }
    }
    if (mission) {
      std::cout << "mmh-goal: mission " << (mission->sequencer.finished() ? "done" : "stopped")
                << ": "
                << (mission->sequencer.finished() ? mission->sequencer.size()
                                                  : mission->sequencer.index())
                << " of " << mission->sequencer.size() << " waypoints reached\n";
      return mission->sequencer.finished() ? 0 : 3;
    }
    std::cout << "mmh-goal: sent " << sent << " GOAL messages (id " << id << ") on "
              << ctx.channel(mmh::channels::kGoal) << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "mmh-goal: " << e.what() << "\n";
    return 1;
  }
}
