// One flight of the mission benchmark (method, world, trial) and its result record, with the
// text form that mmh-bench and its worker processes exchange and that results.json is made of.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>

#include "stop_census.hpp"
#include "time_by_mode.hpp"

namespace mmh::bench {

struct FlightSpec {
  std::string method = "mmh";    // arbiter policy
  double density = 0.1;          // obstacles per m^2 (forest worlds)
  std::string world = "forest";  // "forest", "ego-forest" or a .pcd path
  Eigen::Vector3d size_m = Eigen::Vector3d(50.0, 50.0, 3.0);  // forest box, centred on x = y = 0
  std::string sensor = "depth";                               // "depth" or "lidar"
  int map_index = 0;                                          // 0..maps-1
  int64_t map_seed = 0;                                       // forest seed
  int trial = 0;                                              // 0..trials-1
  int64_t noise_seed = 0;                                     // sensor-noise seed of this trial
  Eigen::Vector3d start = Eigen::Vector3d(-19.95, 0.0, 1.2);
  Eigen::Vector3d goal = Eigen::Vector3d(19.95, 0.0, 1.2);
  std::string id() const;  // unique, file-name safe
};

struct FlightResult {
  FlightSpec spec;
  bool success = false, reached = false, collided = false, timed_out = false;
  double flight_time_s = 0, distance_m = 0, energy = 0;
  int iterations = 0;
  double cost_ms_mean = 0, cost_ms_p50 = 0, cost_ms_p99 = 0;
  int iterations_fpm = 0, iterations_som = 0, iterations_eam = 0;
  double time_bound_s = 0, time_ratio = 0;
  double min_clearance_m = 0;
  int stops = 0;
  FlightCensus census;      // the stops with their causes, and the stalls
  TimeByMode time_by_mode;  // time flown, lost against v_max, and energy flown per mode
  double wall_time_s = 0;
  std::string error;   // non-empty when the flight could not run
  std::string reason;  // non-empty when it flew and failed: why (FlightRecord::failure_reason)
};

// One JSON object per flight (the results.json record) and back; fromJson throws
// nlohmann::json::exception on a malformed record.
nlohmann::json toJson(const FlightResult& r);
FlightResult fromJson(const nlohmann::json& j);

}  // namespace mmh::bench
