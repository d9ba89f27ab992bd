// mmh-stack: flies one mission with every service hosted in this process on memq://, the
// simulator in lock-step (faster than real time; the same seed gives the same flight).
#include <cstdio>
#include <iostream>
#include <sstream>

#include "config_overrides.hpp"
#include "fleet_report.hpp"

#include "mmh/common/cli.hpp"
#include "mmh/common/log.hpp"
#include "mmh/common/node_options.hpp"
#include "mmh/sim/world_file.hpp"
#include "stack.hpp"

namespace {

// A JSON string literal of s (quotes, backslashes and control characters escaped).
std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof(buf), "\\u%04x", static_cast<unsigned char>(c));
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// {"cause": count, ...} in the census's (alphabetical) order.
std::string causeCountsJson(const mmh::FlightCensus& census) {
  std::string out = "{";
  for (const auto& [cause, count] : census.causeCounts()) {
    if (out.size() > 1) out += ", ";
    out += "\"" + cause + "\": " + std::to_string(count);
  }
  return out + "}";
}

// The mission's and the tracking model's fields, only for flights that have them (so the JSON of
// a single goal flown exactly stays as it was).
std::string missionJson(const mmh::sim::MissionMetrics& m) {
  std::ostringstream out;
  if (m.num_waypoints > 1) {
    out << ", \"waypoints\": " << m.num_waypoints << ", \"arrivals\": [";
    for (size_t i = 0; i < m.arrivals.size(); ++i) {
      out << (i ? ", " : "") << "{\"waypoint\": " << m.arrivals[i].waypoint_index + 1
          << ", \"time_s\": " << m.arrivals[i].flight_time_s
          << ", \"speed_mps\": " << m.arrivals[i].speed_mps << "}";
    }
    out << "]";
  }
  if (m.follows_setpoints) {
    out << ", \"tracking_error_rms_m\": " << m.tracking_error_rms_m
        << ", \"tracking_error_max_m\": " << m.tracking_error_max_m;
  }
  return out.str();
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> overrides = mmh::takeSetOptions(&argc, argv);
  std::string set_help;
  mmh::NodeOptions node;
  mmh::sim::SimOptions sim;
  std::string policy, log_path, waypoints_text, mission_path;
  double timeout_s = 120.0, map_loss = 0.0;
  bool json = false, fit_geofence = false;
  std::string export_path;
  int vehicles = 1;
  int seed = static_cast<int>(sim.seed), noise_seed = static_cast<int>(sim.noise_seed);
  mmh::ArgParser parser("mmh-stack",
                        "Flies one mission with mapping, awareness, FPM, SOM, EAM, arbiter and the "
                        "simulator in one process (memq://, lock-step).");
  parser.addString("--config", &node.config_path,
                   "configuration (default: $MMH_CONFIG or deploy/config/default.yaml)");
  parser.addString("--log-level", &node.log_level, "debug, info, warn or error");
  parser.addString("--prefix", &node.prefix, "channel prefix");
  parser.addString("--world", &sim.world, "forest, or a PCD file (surface points of obstacles)");
  parser.addVector3("--size", &sim.size_m, "forest size x,y,z (m)");
  parser.addDouble("--density", &sim.density_per_m2, "forest density (obstacles per m^2)");
  parser.addInt("--seed", &seed, "forest seed");
  parser.addVector3("--start", &sim.start, "start x,y,z");
  parser.addVector3("--goal", &sim.goal, "goal x,y,z");
  parser.addString("--sensor", &sim.sensor, "depth or lidar");
  parser.addString("--follow", &sim.follow,
                   "trajectory (exactly), or setpoint (mmh-setpoint's SETPOINT through the "
                   "tracking model)");
  parser.addString(
      "--waypoints", &waypoints_text,
      "a mission \"x,y,z;x,y,z;...\" instead of --goal (passed at speed, the last a stop)");
  parser.addString("--mission", &mission_path, "a mission file (YAML) instead of --goal");
  parser.addInt("--noise-seed", &noise_seed, "sensor-noise seed");
  parser.addString("--policy", &policy,
                   "arbiter policy: mmh, ego, som, mmh-no-lazy, mmh-no-awareness");
  parser.addDouble("--timeout", &timeout_s, "simulated seconds before giving up");
  parser.addString("--log", &log_path, "write an LCM log of every message (event time = sim time)");
  parser.addDouble("--map-loss", &map_loss,
                   "test switch: share of LOCAL_MAP messages planners lose");
  parser.addFlag("--json", &json, "print the result as one JSON object");
  parser.addString("--set", &set_help,
                   "key=value: override one configuration key (repeatable; a key of "
                   "docs/configuration.md, also one the file leaves out)");
  parser.addInt("--vehicles", &vehicles,
                "vehicles in the one simulation (prefixes <prefix>UAV1_ ..., seeds +0, +1, ...)");
  parser.addFlag("--fit-geofence", &fit_geofence,
                 "with --world FILE.pcd: set geofence.min_m / max_m to the file's bounds plus 1 m "
                 "in x and y (z as configured), and print them");
  parser.addString("--export-world", &export_path,
                   "write the generated world (forest, ego-forest) as a PCD file of surface "
                   "points (0.05 m apart) and exit");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  sim.seed = seed;
  sim.noise_seed = noise_seed;
  mmh::setLogServiceName("mmh-stack");
  try {
    mmh::StackOptions options;
    options.config = mmh::loadConfigWithOverrides(node, overrides);
    if (!export_path.empty()) {
      std::cout << "mmh-stack: " << mmh::sim::exportWorld(sim, export_path) << std::endl;
      return 0;
    }
    if (fit_geofence) {
      std::string report;
      const mmh::Geofence fence = mmh::sim::fitGeofenceToPcd(sim.world, options.config, &report);
      options.config = mmh::sim::configWithGeofence(options.config, fence);
      // On stderr: --json keeps stdout to the one result object.
      std::cerr << "mmh-stack: " << report << std::endl;
    }
    options.sim = sim;
    options.prefix = node.prefix;
    options.policy = policy;
    options.timeout_s = timeout_s;
    options.log_path = log_path;
    options.map_loss = map_loss;
    options.vehicles = vehicles;
    const mmh::MissionRules rules = mmh::loadMissionRules(options.config);
    if (!waypoints_text.empty()) options.waypoints = mmh::parseWaypointList(waypoints_text, rules);
    if (!mission_path.empty()) options.waypoints = mmh::loadMissionFile(mission_path, rules);
    const std::string outside =
        mmh::missionGeofenceViolation(options.waypoints, mmh::loadGeofence(options.config));
    if (!outside.empty()) throw mmh::MissionError(outside);
    // The forest keeps the mission's end clear, and the time bound is computed to it.
    if (!options.waypoints.empty()) options.sim.goal = options.waypoints.back().position;
    mmh::Stack stack(options);
    if (vehicles > 1) return reportFleet(stack, json);
    const mmh::FlightRecord r = stack.fly();
    const auto& m = r.metrics;
    double cost_sum = 0;
    for (const auto& c : r.calls) cost_sum += c.compute_ms;
    const int iterations = static_cast<int>(r.calls.size());
    if (json) {
      // A failure says why (only then, so a success's JSON stays as it was).
      const std::string reason = r.success() ? "" : ", \"reason\": " + jsonString(r.failure_reason);
      std::cout << "{\"result\": \"" << r.end_reason << "\"" << reason
                << ", \"flight_time_s\": " << m.flight_time_s
                << ", \"distance_m\": " << m.distance_m << ", \"energy\": " << m.energy
                << ", \"iterations\": " << iterations << ", \"fpm\": " << r.iterations[1]
                << ", \"som\": " << r.iterations[2] << ", \"eam\": " << r.iterations[3]
                << ", \"cost_ms_mean\": " << (iterations ? cost_sum / iterations : 0.0)
                << ", \"time_bound_s\": " << m.time_bound_s << ", \"stops\": " << r.stops
                << ", \"wall_time_s\": " << r.wall_time_s
                << ", \"stop_causes\": " << causeCountsJson(r.census)
                << ", \"max_calls_without_commit\": " << r.census.max_calls_without_commit
                << ", \"longest_no_progress_s\": " << r.census.longest_no_progress_s
                << ", \"trajectory_digest\": \"" << std::hex << r.trajectory_digest << std::dec
                << "\"" << missionJson(m) << "}\n";
    } else {
      std::cout << "result:        " << r.end_reason << "\n";
      if (!r.success()) std::cout << "reason:        " << r.failure_reason << "\n";
      std::cout << "flight time:   " << m.flight_time_s << " s (bound " << m.time_bound_s << " s)\n"
                << "distance:      " << m.distance_m << " m\n"
                << "energy:        " << m.energy << " m^2/s^5\n"
                << "iterations:    " << iterations << " (FPM " << r.iterations[1] << ", SOM "
                << r.iterations[2] << ", EAM " << r.iterations[3] << "), stops " << r.stops << "\n"
                << "cost/iteration " << (iterations ? cost_sum / iterations : 0.0) << " ms\n"
                << "min clearance: " << m.min_clearance_m << " m\n"
                << "simulated " << r.sim_time_s << " s in " << r.wall_time_s << " s wall\n";
      if (m.num_waypoints > 1) {
        std::cout << "waypoints:     " << m.arrivals.size() << " of " << m.num_waypoints
                  << " reached\n";
        for (const auto& a : m.arrivals) {
          std::cout << "  waypoint " << a.waypoint_index + 1 << ":   at " << a.flight_time_s
                    << " s, " << a.speed_mps << " m/s\n";
        }
      }
      if (m.follows_setpoints) {
        std::cout << "tracking error: rms " << m.tracking_error_rms_m << " m, max "
                  << m.tracking_error_max_m << " m\n";
      }
    }
    return r.success() ? 0 : 3;
  } catch (const mmh::MissionError& e) {
    std::cerr << "mmh-stack: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "mmh-stack: " << e.what() << "\n";
    return 1;
  }
}
