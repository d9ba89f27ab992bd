// Missions of several waypoints (mmh-goal --waypoints "x,y,z;...", --mission FILE.yaml): what a
// waypoint is, how a mission is read, when a waypoint counts as reached, and the sequencer that
// hands the waypoints to the arbiter one after another as GOALs. Waypoints without a stop are
// handed over as soon as the vehicle is within their tolerance, so it passes them at speed; at a
// stop (and at the last waypoint) the vehicle must also have slowed below mission.stop_speed_mps.
// The arbiter's own rules are unchanged: every GOAL is planned for as a goal. The same rule of
// arrival serves the executor (mmh-goal, mmh-stack) and the simulator's ground truth.
#pragma once

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <vector>

#include "mmh/common/config.hpp"
#include "mmh/common/geofence.hpp"

namespace mmh {

struct Waypoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double tolerance_m = 1.0;  // reached within this distance
  bool stop = false;         // come to rest here
};

// Section `mission` of the configuration.
struct MissionRules {
  double pass_tolerance_m = 1.0;  // default tolerance of a waypoint passed at speed
  double stop_tolerance_m = 0.3;  // default tolerance of a stop (and of the last waypoint)
  double stop_speed_mps = 0.2;    // at a stop: reached only when slower than this
};
MissionRules loadMissionRules(const Config& config);

// Bounds of what a mission may ask (bad input gets an error naming them).
constexpr size_t kMaxMissionWaypoints = 1000;
constexpr double kMinWaypointTolerance_m = 0.05;
constexpr double kMaxWaypointTolerance_m = 50.0;

class MissionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "x,y,z;x,y,z;..." (spaces allowed): every waypoint passed at speed but the last, with the
// rules' default tolerances. Throws MissionError naming the bad waypoint.
std::vector<Waypoint> parseWaypointList(const std::string& text, const MissionRules& rules);

// A mission file:
//   waypoints:
//     - position: [x, y, z]     # m, world frame (required)
//       tolerance_m: 0.5        # optional: the rules' default for a pass or a stop
//       stop: true              # optional, false: passed at speed (the last one always stops)
// Throws MissionError naming the file, the waypoint and the key.
std::vector<Waypoint> loadMissionFile(const std::string& path, const MissionRules& rules);
std::vector<Waypoint> parseMissionYaml(const std::string& yaml, const MissionRules& rules,
                                       const std::string& source);

// Empty when every waypoint lies inside the fence; else geofenceViolation's sentence for the first
// one that does not ("waypoint 2 [...] lies outside the geofence ..."): the arbiter would refuse
// it, and the mission would stall there.
std::string missionGeofenceViolation(const std::vector<Waypoint>& waypoints, const Geofence& fence);

// Within the waypoint's tolerance, and, at a stop, slower than stop_speed_mps.
bool waypointReached(const Waypoint& waypoint, const Eigen::Vector3d& position, double speed_mps,
                     double stop_speed_mps);

// Walks a mission: the current waypoint is the GOAL to publish; update() moves on when the
// vehicle reaches it.
class MissionSequencer {
 public:
  // Throws MissionError when `waypoints` is empty. The last waypoint is made a stop.
  MissionSequencer(std::vector<Waypoint> waypoints, double stop_speed_mps);

  // The vehicle's state. Returns true when it reached the current waypoint (then index() has
  // moved on, or finished() is true after the last one).
  bool update(const Eigen::Vector3d& position, const Eigen::Vector3d& velocity);

  int index() const { return index_; }  // of the current waypoint (the last once finished)
  int size() const { return static_cast<int>(waypoints_.size()); }
  const Waypoint& current() const { return waypoints_[static_cast<size_t>(index_)]; }
  const std::vector<Waypoint>& waypoints() const { return waypoints_; }
  bool finished() const { return finished_; }

 private:
  std::vector<Waypoint> waypoints_;
  double stop_speed_mps_;
  int index_ = 0;
  bool finished_ = false;
};

}  // namespace mmh
