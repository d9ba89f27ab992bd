// mmh-test-mapcheck: flies the simulated vehicle round a small square next to its start (by
// publishing a TRAJECTORY, as the arbiter would), rebuilds the LOCAL_MAP stream with
// LocalMapReceiver and compares the map with the forest that mmh-sim generated from the same
// options. Exit 0 when the map matches the world.
#include <cmath>
#include <iostream>
#include <set>

#include "mmh/common/forest.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/common/node_options.hpp"
#include "mmh/mission_status_t.hpp"
#include "mmh/odometry_t.hpp"

namespace {

struct Listener {
  void onOdometry(const mmh::odometry_t& m) {
    last_odometry = m;
    ++odometry;
  }
  void onMap(const mmh::local_map_t& m) {
    ++maps;
    if (receiver.apply(m) == mmh::LocalMapReceiver::Result::kApplied) ++applied;
  }
  void onStatus(const mmh::mission_status_t& m) {
    last_status = m;
    ++statuses;
  }
  mmh::odometry_t last_odometry{};
  mmh::mission_status_t last_status{};
  int odometry = 0, maps = 0, applied = 0, statuses = 0;
  mmh::LocalMapReceiver receiver;
};

// Rest-to-rest minimum-jerk piece from a to b in time T.
mmh::Piece minJerk(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double T) {
  mmh::Piece p;
  p.duration = T;
  const Eigen::Vector3d d = b - a;
  p.coeffs.col(0) = a;
  p.coeffs.col(3) = 10.0 * d / std::pow(T, 3);
  p.coeffs.col(4) = -15.0 * d / std::pow(T, 4);
  p.coeffs.col(5) = 6.0 * d / std::pow(T, 5);
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  mmh::NodeOptions node;
  mmh::ForestSpec spec;
  int seed = 7;
  double timeout_s = 40.0, side_m = 1.2, leg_s = 2.5;
  Eigen::Vector3d expect_goal = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  mmh::ArgParser parser("mmh-test-mapcheck",
                        "Checks mmh-mapping's LOCAL_MAP against mmh-sim's forest.");
  mmh::addNodeOptions(parser, &node);
  parser.addVector3("--size", &spec.size_m, "forest size (as given to mmh-sim)");
  parser.addDouble("--density", &spec.density_per_m2, "forest density (as given to mmh-sim)");
  parser.addInt("--seed", &seed, "forest seed (as given to mmh-sim)");
  parser.addVector3("--start", &spec.start, "start (as given to mmh-sim)");
  parser.addVector3("--goal", &spec.goal, "goal (as given to mmh-sim)");
  parser.addVector3("--expect-goal", &expect_goal, "goal MISSION_STATUS must report (from GOAL)");
  parser.addDouble("--side", &side_m, "side of the square flown next to the start (m)");
  parser.addDouble("--timeout", &timeout_s, "give up after this many seconds");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  spec.seed = static_cast<uint64_t>(seed);
  mmh::setLogServiceName("mmh-test-mapcheck");
  try {
    auto lcm = mmh::openLcm(node.lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-test-mapcheck", node.prefix);
    Listener listener;
    ctx.subscribe(mmh::channels::kOdometry, &Listener::onOdometry, &listener);
    ctx.subscribe(mmh::channels::kLocalMap, &Listener::onMap, &listener);
    ctx.subscribe(mmh::channels::kMissionStatus, &Listener::onStatus, &listener);
    const int64_t deadline = mmh::wallTimeUs() + static_cast<int64_t>(timeout_s * 1e6);
    auto spin = [&](auto done) {
      while (!done() && mmh::wallTimeUs() < deadline) lcm->handleTimeout(50);
      return done();
    };
    if (!spin([&] { return listener.odometry > 0 && listener.applied > 0; })) {
      std::cerr << "FAIL: no ODOMETRY or LOCAL_MAP (odometry " << listener.odometry << ", maps "
                << listener.maps << ")\n";
      return 1;
    }
    // The square: +x, +y, -x, -y from the start, so that the camera looks all round.
    const Eigen::Vector3d s = mmh::toVec3(listener.last_odometry.position);
    const std::vector<Eigen::Vector3d> corners = {s, s + Eigen::Vector3d(side_m, 0, 0),
                                                  s + Eigen::Vector3d(side_m, side_m, 0),
                                                  s + Eigen::Vector3d(0, side_m, 0), s};
    mmh::Trajectory traj;
    for (size_t i = 0; i + 1 < corners.size(); ++i)
      traj.append(minJerk(corners[i], corners[i + 1], leg_s));
    mmh::trajectory_t msg{};
    msg.header.utime = listener.last_odometry.header.utime;
    msg.trajectory_id = 1;
    msg.start_utime = listener.last_odometry.header.utime + 300'000;
    msg.source_mode = 0;
    mmh::toMsg(traj, msg);
    ctx.publish(mmh::channels::kTrajectory, msg);
    const int64_t end_utime =
        msg.start_utime + static_cast<int64_t>(traj.duration() * 1e6) + 1'500'000;
    if (!spin([&] { return listener.last_odometry.header.utime >= end_utime; })) {
      std::cerr << "FAIL: the flight did not finish in time\n";
      return 1;
    }
    // The vehicle flew the square (it follows the trajectory exactly).
    const double flown = (mmh::toVec3(listener.last_odometry.position) - s).norm();
    // Compare the map with the world.
    const auto forest = mmh::generateForest(spec);
    const mmh::VoxelGrid& grid = listener.receiver.grid();
    const double res = grid.resolution();
    const double tol = res * std::sqrt(3.0) / 2 + 1e-3;
    int64_t occupied = 0, occupied_ok = 0, free = 0, free_inside = 0;
    std::set<size_t> seen;
    for (int64_t i = 0; i < grid.numCells(); ++i) {
      const mmh::Occupancy st = grid.atLinear(i);
      if (st == mmh::Occupancy::kUnknown) continue;
      const Eigen::Vector3d c = grid.centerOfLocal(grid.localFromLinear(i));
      const double d = mmh::distanceToForest(forest, c);
      if (st == mmh::Occupancy::kOccupied) {
        ++occupied;
        if (std::abs(d) <= tol) {
          ++occupied_ok;
          for (size_t k = 0; k < forest.size(); ++k) {
            if (std::abs((c.head<2>() - forest[k].center).norm() - forest[k].radius) <= tol)
              seen.insert(k);
          }
        }
      } else {
        ++free;
        if (d < -tol) ++free_inside;
      }
    }
    // Cylinders whose surface comes within 3.5 m of the start: the camera sweeps all round it.
    int near = 0, near_seen = 0;
    for (size_t k = 0; k < forest.size(); ++k) {
      if ((forest[k].center - s.head<2>()).norm() - forest[k].radius < 3.5) {
        ++near;
        near_seen += seen.count(k) > 0;
      }
    }
    std::cout << "odometry " << listener.odometry << ", LOCAL_MAP " << listener.maps << " (applied "
              << listener.applied << ", gaps " << listener.receiver.gapsDetected() << "), occupied "
              << occupied << " (" << occupied_ok << " on a cylinder surface), free " << free << " ("
              << free_inside << " inside a cylinder), cylinders mapped " << seen.size()
              << ", of those within 3.5 m of the start " << near_seen << " of " << near
              << ", back at start within " << flown << " m\n";
    bool ok = true;
    auto check = [&](bool cond, const std::string& what) {
      if (!cond) {
        std::cerr << "FAIL: " << what << "\n";
        ok = false;
      }
    };
    check(flown < 0.01, "the vehicle did not fly the square back to its start");
    check(occupied > 500, "too few occupied cells");
    check(occupied_ok >= 0.99 * occupied, "occupied cells off the cylinders");
    check(free > 20000, "too little free space");
    check(free_inside <= 0.001 * free, "free cells inside cylinders");
    check(near > 0 && near_seen * 10 >= near * 8, "cylinders near the start not mapped");
    check(listener.statuses > 0, "no MISSION_STATUS");
    check(!listener.last_status.collided, "collision reported");
    if (expect_goal.allFinite()) {
      check((mmh::toVec3(listener.last_status.goal) - expect_goal).norm() < 1e-9,
            "MISSION_STATUS does not report the goal sent on GOAL");
    }
    std::cout << (ok ? "PASS" : "FAIL") << "\n";
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "mmh-test-mapcheck: " << e.what() << "\n";
    return 1;
  }
}
