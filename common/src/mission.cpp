#include "mmh/common/mission.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "mmh/common/cli.hpp"

namespace mmh {
namespace {

std::string trimmed(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

void checkCount(size_t n, const std::string& source) {
  if (n == 0) throw MissionError(source + ": the mission has no waypoint");
  if (n > kMaxMissionWaypoints)
    throw MissionError(source + ": " + std::to_string(n) + " waypoints, more than the " +
                       std::to_string(kMaxMissionWaypoints) + " a mission may have");
}

// The last waypoint always stops; defaults for tolerances not given (negative).
void finish(std::vector<Waypoint>* waypoints, const MissionRules& rules) {
  waypoints->back().stop = true;
  for (Waypoint& w : *waypoints) {
    if (w.tolerance_m < 0.0)
      w.tolerance_m = w.stop ? rules.stop_tolerance_m : rules.pass_tolerance_m;
  }
}

}  // namespace

MissionRules loadMissionRules(const Config& config) {
  MissionRules r;
  r.pass_tolerance_m = config.getDouble("mission.pass_tolerance_m");
  r.stop_tolerance_m = config.getDouble("mission.stop_tolerance_m");
  r.stop_speed_mps = config.getDouble("mission.stop_speed_mps");
  return r;
}

std::vector<Waypoint> parseWaypointList(const std::string& text, const MissionRules& rules) {
  std::vector<Waypoint> out;
  std::stringstream s(text);
  std::string part;
  while (std::getline(s, part, ';')) {
    part = trimmed(part);
    if (part.empty() && s.eof()) break;  // a trailing ';'
    Waypoint w;
    std::string compact;
    for (char c : part)
      if (c != ' ' && c != '\t') compact += c;
    if (!parseVector3(compact, &w.position))
      throw MissionError("--waypoints: waypoint " + std::to_string(out.size() + 1) + " '" + part +
                         "' is not x,y,z (three finite numbers in metres)");
    w.tolerance_m = -1.0;
    out.push_back(w);
  }
  checkCount(out.size(), "--waypoints");
  finish(&out, rules);
  return out;
}

std::vector<Waypoint> parseMissionYaml(const std::string& yaml, const MissionRules& rules,
                                       const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    throw MissionError(source + ": not valid YAML: " + e.what());
  }
  if (!root.IsMap()) throw MissionError(source + ": expected a map with the key 'waypoints'");
  for (const auto& kv : root) {
    const std::string key = kv.first.as<std::string>();
    if (key != "waypoints") throw MissionError(source + ": unknown key '" + key + "'");
  }
  const YAML::Node list = root["waypoints"];
  if (!list || !list.IsSequence())
    throw MissionError(source + ": 'waypoints' must be a list of waypoints");
  std::vector<Waypoint> out;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string where = source + ": waypoint " + std::to_string(i + 1);
    const YAML::Node node = list[i];
    if (!node.IsMap()) throw MissionError(where + ": expected a map with 'position'");
    Waypoint w;
    w.tolerance_m = -1.0;
    bool has_position = false;
    try {
      for (const auto& kv : node) {
        const std::string key = kv.first.as<std::string>();
        if (key == "position") {
          const YAML::Node p = kv.second;
          if (!p.IsSequence() || p.size() != 3)
            throw MissionError(where + ": 'position' must be [x, y, z]");
          for (int k = 0; k < 3; ++k) w.position[k] = p[k].as<double>();
          if (!w.position.allFinite()) throw MissionError(where + ": 'position' must be finite");
          has_position = true;
        } else if (key == "tolerance_m") {
          w.tolerance_m = kv.second.as<double>();
          if (!(w.tolerance_m >= kMinWaypointTolerance_m &&
                w.tolerance_m <= kMaxWaypointTolerance_m))
            throw MissionError(where + ": 'tolerance_m' must be in [" +
                               std::to_string(kMinWaypointTolerance_m) + ", " +
                               std::to_string(kMaxWaypointTolerance_m) + "] m");
        } else if (key == "stop") {
          w.stop = kv.second.as<bool>();
        } else {
          throw MissionError(where + ": unknown key '" + key +
                             "' (a waypoint has position, tolerance_m, stop)");
        }
      }
    } catch (const YAML::Exception& e) {
      throw MissionError(where + ": " + e.what());
    }
    if (!has_position) throw MissionError(where + ": 'position' is missing");
    out.push_back(w);
  }
  checkCount(out.size(), source);
  finish(&out, rules);
  return out;
}

std::vector<Waypoint> loadMissionFile(const std::string& path, const MissionRules& rules) {
  std::ifstream in(path);
  if (!in) throw MissionError(path + ": cannot read the mission file");
  std::stringstream text;
  text << in.rdbuf();
  return parseMissionYaml(text.str(), rules, path);
}

std::string missionGeofenceViolation(const std::vector<Waypoint>& waypoints,
                                     const Geofence& fence) {
  for (size_t i = 0; i < waypoints.size(); ++i) {
    const std::string why =
        geofenceViolation(fence, waypoints[i].position, "waypoint " + std::to_string(i + 1));
    if (!why.empty()) return why;
  }
  return "";
}

bool waypointReached(const Waypoint& waypoint, const Eigen::Vector3d& position, double speed_mps,
                     double stop_speed_mps) {
  if ((position - waypoint.position).norm() > waypoint.tolerance_m) return false;
  return !waypoint.stop || speed_mps <= stop_speed_mps;
}

MissionSequencer::MissionSequencer(std::vector<Waypoint> waypoints, double stop_speed_mps)
    : waypoints_(std::move(waypoints)), stop_speed_mps_(stop_speed_mps) {
  if (waypoints_.empty()) throw MissionError("a mission needs at least one waypoint");
  waypoints_.back().stop = true;
}

bool MissionSequencer::update(const Eigen::Vector3d& position, const Eigen::Vector3d& velocity) {
  if (finished_ || !waypointReached(current(), position, velocity.norm(), stop_speed_mps_))
    return false;
  if (index_ + 1 < size()) {
    ++index_;
  } else {
    finished_ = true;
  }
  return true;
}

}  // namespace mmh
