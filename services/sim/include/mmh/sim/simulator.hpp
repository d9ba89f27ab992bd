// The whole simulation without LCM: world, vehicle, sensor and mission metrics advanced in fixed
// steps of simulated time. SimNode (node/) adapts it to messages; tests and benchmarks use it
// directly. Deterministic: the same options give the same flight.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>

#include "mmh/common/forest.hpp"
#include "mmh/sim/ego_forest.hpp"
#include "mmh/sim/mission.hpp"
#include "mmh/sim/sensor.hpp"
#include "mmh/sim/sim_params.hpp"
#include "mmh/sim/vehicle.hpp"
#include "mmh/sim/world.hpp"

namespace mmh::sim {

// Simulated time at the start of a lock-step run (1000 s): fixed, so that a seed gives the same
// flight, message for message; well above 0 so that "time minus a few seconds" stays positive.
constexpr int64_t kLockstepStartUtime = 1'000'000'000;

// What a run simulates (mmh-sim's command line).
struct SimOptions {
  std::string world = "forest";  // "forest", "ego-forest" or the path of a .pcd file
  Eigen::Vector3d size_m = Eigen::Vector3d(50.0, 50.0, 3.0);  // forest box, centred on x = y = 0
  double density_per_m2 = 0.1;
  int64_t seed = 7;  // forest seed
  Eigen::Vector3d start = Eigen::Vector3d(-19.95, 0.0, 1.2);
  Eigen::Vector3d goal = Eigen::Vector3d(19.95, 0.0, 1.2);
  std::string sensor = "depth";  // "depth" or "lidar"
  int64_t noise_seed = 1;
  // Initial heading; NaN: towards the goal.
  double initial_yaw_deg = std::numeric_limits<double>::quiet_NaN();
  int64_t start_utime = kLockstepStartUtime;
  // What the vehicle flies: "trajectory" (the committed TRAJECTORY, exactly) or "setpoint" (the
  // SETPOINT stream of mmh-setpoint, through the tracking model).
  std::string follow = "trajectory";
};

// The generators' specifications of the forest / ego-forest the options describe (size,
// density, seed, start and goal), for the simulated world and for --export-world alike.
ForestSpec forestSpecOf(const SimOptions& options);
EgoForestSpec egoForestSpecOf(const SimOptions& options);

// The world the options describe. Throws std::runtime_error with the reason (unreadable PCD,
// impossible forest, unknown world).
std::unique_ptr<World> makeWorld(const SimOptions& options, const SimParams& params);
SensorKind parseSensorKind(const std::string& name);  // throws std::runtime_error

class Simulator {
 public:
  // Throws std::runtime_error for bad options (see makeWorld; also a start inside an obstacle, a
  // start or goal outside the geofence or, in a PCD world, outside the points' bounds in x and y,
  // an unknown --follow).
  Simulator(const SimParams& params, const SimOptions& options);
  Simulator(const SimParams& params, const SimOptions& options, std::unique_ptr<World> world);

  struct StepResult {
    bool scan = false;    // a sensor frame is ready in lastScan()
    bool status = false;  // MISSION_STATUS is due (rate, or an event below)
    bool event = false;   // reached or collided became true in this step
  };
  // Advances simulated time by one step (params.step_s).
  StepResult step();

  void commitTrajectory(std::shared_ptr<const Trajectory> trajectory, int64_t start_utime,
                        int64_t trajectory_id) {
    vehicle_.commit(std::move(trajectory), start_utime, trajectory_id);
  }
  void setGoal(const Eigen::Vector3d& goal, int64_t goal_id) { monitor_.setGoal(goal, goal_id); }
  // A goal that is one waypoint of a mission (goal_t's mission fields).
  void setMissionGoal(const MissionGoal& goal) { monitor_.setMissionGoal(goal); }
  // The arbiter moved the current goal (MissionMonitor::acceptMovedGoal).
  bool acceptMovedGoal(const Eigen::Vector3d& moved) {
    return monitor_.acceptMovedGoal(moved, params_.goal_relocate_radius_m);
  }
  // Following setpoints: the newest SETPOINT.
  void setSetpoint(const SetpointSample& setpoint) { vehicle_.setSetpoint(setpoint); }
  bool followsSetpoints() const { return vehicle_.followsSetpoints(); }

  int64_t nowUtime() const { return vehicle_.nowUtime(); }
  int64_t stepUs() const { return step_us_; }
  const Vehicle& vehicle() const { return vehicle_; }
  const World& world() const { return *world_; }
  const Sensor& sensor() const { return sensor_; }
  const Scan& lastScan() const { return scan_; }
  const MissionMetrics& metrics() const { return monitor_.metrics(); }
  // Reached, or collided with sim.stop_on_collision.
  bool finished() const;
  const SimParams& params() const { return params_; }
  const SimOptions& options() const { return options_; }

 private:
  SimParams params_;
  SimOptions options_;
  std::unique_ptr<World> world_;
  int64_t step_us_;
  Vehicle vehicle_;
  Sensor sensor_;
  MissionMonitor monitor_;
  Scan scan_;
  std::vector<FlownPart> flown_;
  int64_t scans_done_ = 0, statuses_done_ = 0;
};

}  // namespace mmh::sim
