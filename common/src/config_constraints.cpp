#include "mmh/common/config_constraints.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mmh/common/config_registry.hpp"
#include "mmh/common/replan_lead.hpp"
#include "mmh/common/vehicle_limits.hpp"

namespace mmh {
namespace {

std::string quoted(const std::string& key, double value) {
  std::ostringstream s;
  s << "'" << key << "' = " << value;
  return s.str();
}

// a <= b + offset (both doubles).
ConfigConstraint atMost(const std::string& a, const std::string& b, double offset,
                        const std::string& why) {
  std::ostringstream rule;
  rule << a << " <= " << b;
  if (offset != 0.0) rule << (offset > 0 ? " + " : " - ") << std::abs(offset);
  return {{a, b}, rule.str(), why, [a, b, offset](const Config& c) -> std::string {
            const double va = c.getDouble(a), vb = c.getDouble(b);
            if (va <= vb + offset) return "";
            std::ostringstream s;
            s << quoted(a, va) << " exceeds " << quoted(b, vb);
            if (offset != 0.0) s << (offset > 0 ? " + " : " - ") << std::abs(offset);
            return s.str();
          }};
}

// a >= b + offset (both doubles).
ConfigConstraint atLeast(const std::string& a, const std::string& b, double offset,
                         const std::string& why) {
  std::ostringstream rule;
  rule << a << " >= " << b;
  if (offset != 0.0) rule << (offset > 0 ? " + " : " - ") << std::abs(offset);
  return {{a, b}, rule.str(), why, [a, b, offset](const Config& c) -> std::string {
            const double va = c.getDouble(a), vb = c.getDouble(b);
            // A small tolerance: 0.25 + 0.02 is not exactly 0.27 in binary.
            if (va >= vb + offset - 1e-9) return "";
            std::ostringstream s;
            s << quoted(a, va) << " is below " << quoted(b, vb);
            if (offset != 0.0) s << (offset > 0 ? " + " : " - ") << std::abs(offset);
            return s.str();
          }};
}

std::vector<ConfigConstraint> buildConstraints() {
  std::vector<ConfigConstraint> c;
  c.push_back({{"geofence.min_m", "geofence.max_m"},
               "geofence.max_m > geofence.min_m on every axis",
               "the geofence must be a non-empty box",
               [](const Config& config) -> std::string {
                 const Eigen::Vector3d lo = config.getVector3("geofence.min_m");
                 const Eigen::Vector3d hi = config.getVector3("geofence.max_m");
                 if ((hi.array() > lo.array()).all()) return "";
                 return "'geofence.max_m' must exceed 'geofence.min_m' on every axis";
               }});
  c.push_back(atMost("arbiter.check_inflation_m", "map.inflation_m", 0.0,
                     "a freshly verified answer must not look colliding to the arbiter"));
  c.push_back({{"arbiter.answer_deadline_s", "arbiter.replan_lead_s"},
               "arbiter.answer_deadline_s <= arbiter.replan_lead_s (when replan_lead_s > 0)",
               "an answer must arrive before its trajectory takes effect",
               [](const Config& config) -> std::string {
                 const double deadline = config.getDouble("arbiter.answer_deadline_s");
                 const double lead = config.getDouble("arbiter.replan_lead_s");
                 if (lead <= 0.0 || deadline <= lead) return "";
                 return quoted("arbiter.answer_deadline_s", deadline) + " exceeds " +
                        quoted("arbiter.replan_lead_s", lead);
               }});
  c.push_back(atLeast("arbiter.max_answer_deadline_s", "arbiter.answer_deadline_s", 0.0,
                      "the latency budget only lengthens the configured deadline"));
  c.push_back(atLeast("arbiter.max_slowed_answer_deadline_s", "arbiter.max_answer_deadline_s", 0.0,
                      "the deadline grows past the full-speed one only with the speed lowered"));
  c.push_back({{"map.window_size_m", "vehicle.max_vel_mps", "arbiter.planning_horizon_s"},
               "map.window_size_m x and y >= 2 x vehicle.max_vel_mps x arbiter.planning_horizon_s",
               "the local target (up to v_max x horizon away) must lie inside the map window",
               [](const Config& config) -> std::string {
                 const Eigen::Vector3d window = config.getVector3("map.window_size_m");
                 const double v_max = config.getDouble("vehicle.max_vel_mps");
                 const double horizon = config.getDouble("arbiter.planning_horizon_s");
                 const double range = v_max * horizon;
                 if (std::min(window.x(), window.y()) >= 2.0 * range - 1e-9) return "";
                 std::ostringstream s;
                 s << "'map.window_size_m' (x, y) = (" << window.x() << ", " << window.y()
                   << ") is smaller than twice the planning range 'vehicle.max_vel_mps' x "
                      "'arbiter.planning_horizon_s' = "
                   << range << " m";
                 return s.str();
               }});
  c.push_back({{"vehicle.max_vel_mps", "vehicle.max_acc_mps2", "arbiter.replan_lead_s",
                "arbiter.answer_deadline_s", "arbiter.max_answer_deadline_s", "arbiter.stale_map_s",
                "awareness.sensor_range_m"},
               "vehicle.max_vel_mps^2 / (2 vehicle.max_acc_mps2) + vehicle.max_vel_mps x "
               "(longest replan lead + arbiter.stale_map_s) <= awareness.sensor_range_m, the "
               "longest lead being arbiter.max_answer_deadline_s + arbiter.replan_lead_s - "
               "arbiter.answer_deadline_s",
               "at full speed the vehicle must be able to stop within what its sensor sees, after "
               "the longest reaction time (the replan lead of a loaded computer) and the longest "
               "map delay it flies on",
               [](const Config& config) -> std::string {
                 const double v = config.getDouble("vehicle.max_vel_mps");
                 const double a = config.getDouble("vehicle.max_acc_mps2");
                 const double lead =
                     replanLeadFor(config.getDouble("arbiter.max_answer_deadline_s"),
                                   config.getDouble("arbiter.replan_lead_s"),
                                   config.getDouble("arbiter.answer_deadline_s"));
                 const double latency = lead + config.getDouble("arbiter.stale_map_s");
                 const double range = config.getDouble("awareness.sensor_range_m");
                 const double needed = stoppingDistance(v, a) + v * latency;
                 if (needed <= range + 1e-9) return "";
                 std::ostringstream s;
                 s << "stopping from 'vehicle.max_vel_mps' = " << v
                   << " m/s at 'vehicle.max_acc_mps2' = " << a << " m/s^2 after the longest "
                   << "replan lead (" << lead << " s, from 'arbiter.max_answer_deadline_s') + "
                   << "'arbiter.stale_map_s' = " << latency << " s takes " << needed
                   << " m, beyond 'awareness.sensor_range_m' = " << range
                   << " m: lower the speed or 'arbiter.max_answer_deadline_s', or use a sensor of "
                      "longer range";
                 return s.str();
               }});
  const std::string escape_why =
      "a planner's way out of the margin must not end inside the arbiter's check margin";
  c.push_back(
      atLeast("som.start_escape_clearance_m", "arbiter.check_inflation_m", 0.02, escape_why));
  c.push_back(
      atLeast("eam.start_escape_clearance_m", "arbiter.check_inflation_m", 0.02, escape_why));
  c.push_back({{"eam.fine_knot_span_s", "eam.knot_span_s"},
               "eam.fine_knot_span_s = 0 or < eam.knot_span_s",
               "EAM's second plan uses a finer knot span than its first",
               [](const Config& config) -> std::string {
                 const double fine = config.getDouble("eam.fine_knot_span_s");
                 const double span = config.getDouble("eam.knot_span_s");
                 if (fine == 0.0 || fine < span) return "";
                 return quoted("eam.fine_knot_span_s", fine) + " is not below " +
                        quoted("eam.knot_span_s", span);
               }});
  c.push_back(atLeast("sim.lidar.vmax_deg", "sim.lidar.vmin_deg", 0.0,
                      "the LiDAR's elevation interval must not be empty"));
  c.push_back(atLeast("mapping.occupancy_threshold", "mapping.clamp_min", 0.0,
                      "a clamped cell must be able to fall below the threshold"));
  c.push_back(atMost("mapping.occupancy_threshold", "mapping.clamp_max", 0.0,
                     "a clamped cell must be able to rise above the threshold"));
  return c;
}

bool available(const Config& config, const std::string& key) {
  return config.has(key) || !registeredConfigKey(key).required;
}

}  // namespace

const std::vector<ConfigConstraint>& configConstraints() {
  static const std::vector<ConfigConstraint> constraints = buildConstraints();
  return constraints;
}

std::vector<std::string> constraintViolations(const Config& config) {
  std::vector<std::string> out;
  for (const ConfigConstraint& constraint : configConstraints()) {
    if (!std::all_of(constraint.keys.begin(), constraint.keys.end(),
                     [&](const std::string& k) { return available(config, k); }))
      continue;
    std::string what;
    try {
      what = constraint.violation(config);
    } catch (const ConfigError&) {
      continue;  // an unreadable value: reported by whoever reads it
    }
    if (!what.empty()) {
      out.push_back(config.source() + ": " + what + " (" + constraint.rule + ": " + constraint.why +
                    ")");
    }
  }
  return out;
}

void checkConfigConstraints(const Config& config) {
  const std::vector<std::string> violations = constraintViolations(config);
  if (violations.empty()) return;
  std::string message = violations.front();
  for (size_t i = 1; i < violations.size(); ++i) message += "\n" + violations[i];
  throw ConfigError(message);
}

}  // namespace mmh
