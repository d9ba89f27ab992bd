// mmh-sim: the simulated world, vehicle and sensor as a process, paced by the wall clock
// (--realtime, the default; --speed scales it). Lock-step runs use SimNode inside mmh-stack.
#include <algorithm>
#include <iostream>
#include <thread>

#include "mmh/common/node_options.hpp"
#include "mmh/sim/world_file.hpp"
#include "sim_node.hpp"

int main(int argc, char** argv) {
  mmh::NodeOptions node;
  mmh::SimOptions o;
  int seed = static_cast<int>(o.seed), noise_seed = static_cast<int>(o.noise_seed);
  bool realtime = false, exit_when_finished = false, fit_geofence = false;
  std::string export_path;
  double speed = 1.0, duration_s = 0.0;
  mmh::ArgParser parser("mmh-sim",
                        "Simulated UAV: random forest or PCD world, vehicle that follows the "
                        "committed TRAJECTORY (or the SETPOINT stream), depth camera or LiDAR, "
                        "mission ground truth.");
  mmh::addNodeOptions(parser, &node);
  parser.addString(
      "--world", &o.world,
      "forest, ego-forest (EGO-Planner's pillars and rings), or the path of a .pcd file");
  parser.addVector3("--size", &o.size_m,
                    "forest / ego-forest box x,y,z in m (centred on x = y = 0)");
  parser.addDouble("--density", &o.density_per_m2, "forest obstacles per square metre");
  parser.addInt("--seed", &seed, "forest seed");
  parser.addVector3("--start", &o.start, "start position x,y,z (m)");
  parser.addVector3("--goal", &o.goal,
                    "goal x,y,z (m): kept clear in the forest, used until a GOAL arrives");
  parser.addString("--sensor", &o.sensor, "depth or lidar");
  parser.addString("--follow", &o.follow,
                   "what the vehicle flies: trajectory (the committed TRAJECTORY, exactly) or "
                   "setpoint (mmh-setpoint's SETPOINT, through the tracking model sim.tracking.*)");
  parser.addInt("--noise-seed", &noise_seed, "seed of the range noise (sim.*.range_noise_m)");
  parser.addDouble("--yaw-deg", &o.initial_yaw_deg,
                   "initial heading in degrees (nan: towards the goal)");
  parser.addFlag("--realtime", &realtime,
                 "pace simulated time by the wall clock (the only mode of this executable; "
                 "lock-step runs drive SimNode inside mmh-stack)");
  parser.addDouble("--speed", &speed, "simulated seconds per wall-clock second");
  parser.addDouble("--duration", &duration_s, "stop after this many simulated seconds (0: never)");
  parser.addFlag("--exit-when-finished", &exit_when_finished,
                 "stop once the goal is reached (or on collision with sim.stop_on_collision)");
  parser.addFlag("--fit-geofence", &fit_geofence,
                 "with --world FILE.pcd: set geofence.min_m / max_m to the file's bounds plus 1 m "
                 "in x and y (z as configured), and print them");
  parser.addString("--export-world", &export_path,
                   "write the generated world (forest, ego-forest) as a PCD file of surface "
                   "points (0.05 m apart) and exit");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  o.seed = seed;
  o.noise_seed = noise_seed;
  if (!(speed > 0.0 && speed <= 1000.0)) {
    std::cerr << "mmh-sim: --speed must be in (0, 1000]\n";
    return 1;
  }
  mmh::setLogServiceName("mmh-sim");
  try {
    mmh::Config config = mmh::loadNodeConfig(node);
    if (!export_path.empty()) {
      std::cout << "mmh-sim: " << mmh::sim::exportWorld(o, export_path) << std::endl;
      return 0;
    }
    if (fit_geofence) {
      std::string report;
      const mmh::Geofence fence = mmh::sim::fitGeofenceToPcd(o.world, config, &report);
      config = mmh::sim::configWithGeofence(config, fence);
      std::cout << "mmh-sim: " << report << std::endl;
    }
    const auto max_scan_lag_us = static_cast<int64_t>(config.getDouble("sim.max_scan_lag_s") * 1e6);
    auto lcm = mmh::openLcm(node.lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-sim", node.prefix);
    // Real time: simulated time starts at the wall clock, so every process shares one clock.
    const int64_t wall0 = mmh::wallTimeUs();
    o.start_utime = wall0;
    mmh::SimNode sim(ctx, config, o);
    mmh::installStopHandlers();
    ctx.setState(mmh::heartbeat_t::STATE_OK, "");
    ctx.publishHeartbeat();
    const int64_t sim0 = sim.nowUtime();
    const int64_t step_us = sim.simulator().stepUs();
    while (!mmh::stopRequested()) {
      // Wall time at which the next step is due; handle messages until then.
      const int64_t due = wall0 + static_cast<int64_t>(
                                      static_cast<double>(sim.nowUtime() + step_us - sim0) / speed);
      for (;;) {
        const int64_t now = mmh::wallTimeUs();
        const int64_t wait_ms = (due - now) / 1000;
        if (lcm->handleTimeout(static_cast<int>(std::clamp<int64_t>(wait_ms, 0, 100))) < 0) {
          // SIGINT/SIGTERM interrupt the wait (EINTR): a stop, reported with the metrics below.
          if (mmh::stopRequested()) break;
          mmh::logError("mmh-sim: LCM handle failed; stopping");
          return 1;
        }
        if (mmh::wallTimeUs() >= due || mmh::stopRequested()) break;
        if (wait_ms <= 0) std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
      if (mmh::stopRequested()) break;
      // Far behind the wall clock (the process was stopped or starved), the steps run back to
      // back to catch up: their sensor frames are stale, and a burst of them would overflow the
      // receivers' UDP buffers (losing e.g. a TRAJECTORY), so only odometry is sent then.
      sim.step(mmh::wallTimeUs() - due < max_scan_lag_us);
      ctx.maybePublishHeartbeat(mmh::wallTimeUs());
      if (exit_when_finished && sim.finished()) break;
      if (duration_s > 0.0 && (sim.nowUtime() - sim0) * 1e-6 >= duration_s) break;
    }
    const mmh::sim::MissionMetrics& m = sim.metrics();
    std::cout << "mmh-sim: reached=" << m.reached << " collided=" << m.collided
              << " flight_time_s=" << m.flight_time_s << " distance_m=" << m.distance_m
              << " energy=" << m.energy << " min_clearance_m=" << m.min_clearance_m
              << " time_bound_s=" << m.time_bound_s;
    if (m.follows_setpoints) {
      std::cout << " tracking_error_rms_m=" << m.tracking_error_rms_m
                << " tracking_error_max_m=" << m.tracking_error_max_m;
    }
    std::cout << std::endl;
    ctx.setState(mmh::heartbeat_t::STATE_STOPPING, "stopped");
    ctx.publishHeartbeat();
    return 0;
  } catch (const mmh::ConfigError& e) {
    std::cerr << "mmh-sim: " << e.what() << "\n";
    return 1;
  } catch (const mmh::LcmError& e) {
    std::cerr << "mmh-sim: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "mmh-sim: " << e.what() << "\n";
    return 1;
  }
}
