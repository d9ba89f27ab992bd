#include "flight_spec.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace mmh::bench {
namespace {

// JSON has no NaN/Inf: write null, read null back as NaN.
nlohmann::json number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
}
double number(const nlohmann::json& j) {
  return j.is_null() ? NAN : j.get<double>();
}

nlohmann::json toJson(const ModeFailure& f) {
  return nlohmann::json{{"mode", f.mode}, {"reason", f.reason}, {"text", f.text}};
}

nlohmann::json toJson(const StopRecord& s) {
  nlohmann::json failed = nlohmann::json::array();
  for (const ModeFailure& f : s.failed_modes) failed.push_back(toJson(f));
  return nlohmann::json{
      {"time_s", s.time_s},         {"trigger", s.trigger},
      {"cause", s.cause},           {"detail", s.detail},
      {"failed_modes", failed},     {"failed_decisions_before", s.failed_decisions_before},
      {"held_s", number(s.held_s)}, {"lowest_speed_mps", number(s.lowest_speed_mps)}};
}

StopRecord stopFromJson(const nlohmann::json& j) {
  StopRecord s;
  s.time_s = j.at("time_s").get<double>();
  s.trigger = j.at("trigger").get<std::string>();
  s.cause = j.at("cause").get<std::string>();
  s.detail = j.at("detail").get<std::string>();
  for (const auto& f : j.at("failed_modes")) {
    s.failed_modes.push_back(ModeFailure{f.at("mode").get<std::string>(),
                                         f.at("reason").get<std::string>(),
                                         f.at("text").get<std::string>()});
  }
  s.failed_decisions_before = j.at("failed_decisions_before").get<int>();
  // Not in results written before the census measured them: unknown, never "at rest".
  s.held_s = j.contains("held_s") ? number(j.at("held_s")) : NAN;
  s.lowest_speed_mps = j.contains("lowest_speed_mps") ? number(j.at("lowest_speed_mps")) : NAN;
  return s;
}

// The mode slots of TimeByMode by name, as results.json writes them.
constexpr const char* kModeSlotNames[kModeSlots] = {"none", "fpm", "som", "eam", "stop"};

nlohmann::json modeSlotsJson(const std::array<double, kModeSlots>& values) {
  nlohmann::json j = nlohmann::json::object();
  for (int i = 0; i < kModeSlots; ++i) j[kModeSlotNames[i]] = number(values[i]);
  return j;
}

// Records written before the field existed have none: zeros.
std::array<double, kModeSlots> modeSlotsFromJson(const nlohmann::json& j, const char* key) {
  std::array<double, kModeSlots> values{};
  if (!j.contains(key)) return values;
  for (int i = 0; i < kModeSlots; ++i) values[i] = number(j.at(key).at(kModeSlotNames[i]));
  return values;
}

}  // namespace

std::string FlightSpec::id() const {
  std::ostringstream s;
  s << method << "_d" << std::fixed << std::setprecision(2) << density << "_m" << map_index << "_t"
    << trial;
  return s.str();
}

nlohmann::json toJson(const FlightResult& r) {
  const FlightSpec& f = r.spec;
  nlohmann::json stop_events = nlohmann::json::array();
  for (const StopRecord& s : r.census.stops) stop_events.push_back(toJson(s));
  return nlohmann::json{
      {"method", f.method},
      {"density", f.density},
      {"world", f.world},
      {"map_index", f.map_index},
      {"map_seed", f.map_seed},
      {"trial", f.trial},
      {"noise_seed", f.noise_seed},
      {"start", {f.start.x(), f.start.y(), f.start.z()}},
      {"goal", {f.goal.x(), f.goal.y(), f.goal.z()}},
      {"success", r.success},
      {"reached", r.reached},
      {"collided", r.collided},
      {"timed_out", r.timed_out},
      {"flight_time_s", number(r.flight_time_s)},
      {"distance_m", number(r.distance_m)},
      {"energy", number(r.energy)},
      {"iterations", r.iterations},
      {"cost_ms_mean", number(r.cost_ms_mean)},
      {"cost_ms_p50", number(r.cost_ms_p50)},
      {"cost_ms_p99", number(r.cost_ms_p99)},
      {"mode_iterations",
       {{"fpm", r.iterations_fpm}, {"som", r.iterations_som}, {"eam", r.iterations_eam}}},
      {"time_bound_s", number(r.time_bound_s)},
      {"time_ratio", number(r.time_ratio)},
      {"min_clearance_m", number(r.min_clearance_m)},
      {"stops", r.stops},
      {"wall_time_s", number(r.wall_time_s)},
      {"error", r.error},
      {"reason", r.reason},
      {"sensor", f.sensor},
      {"size", {f.size_m.x(), f.size_m.y(), f.size_m.z()}},
      {"stop_causes", r.census.causeCounts()},
      {"stop_events", stop_events},
      {"max_calls_without_commit", r.census.max_calls_without_commit},
      {"longest_no_progress_s", number(r.census.longest_no_progress_s)},
      {"longest_no_progress_from_s", number(r.census.longest_no_progress_from_s)},
      {"time_by_mode_s", modeSlotsJson(r.time_by_mode.time_s)},
      {"time_lost_by_mode_s", modeSlotsJson(r.time_by_mode.lost_s)},
      {"energy_by_mode", modeSlotsJson(r.time_by_mode.energy)},
  };
}

FlightResult fromJson(const nlohmann::json& j) {
  FlightResult r;
  FlightSpec& f = r.spec;
  f.method = j.at("method").get<std::string>();
  f.density = j.at("density").get<double>();
  f.world = j.at("world").get<std::string>();
  f.map_index = j.at("map_index").get<int>();
  f.map_seed = j.at("map_seed").get<int64_t>();
  f.trial = j.at("trial").get<int>();
  f.noise_seed = j.at("noise_seed").get<int64_t>();
  for (int i = 0; i < 3; ++i) {
    f.start[i] = j.at("start").at(i).get<double>();
    f.goal[i] = j.at("goal").at(i).get<double>();
  }
  r.success = j.at("success").get<bool>();
  r.reached = j.at("reached").get<bool>();
  r.collided = j.at("collided").get<bool>();
  r.timed_out = j.at("timed_out").get<bool>();
  r.flight_time_s = number(j.at("flight_time_s"));
  r.distance_m = number(j.at("distance_m"));
  r.energy = number(j.at("energy"));
  r.iterations = j.at("iterations").get<int>();
  r.cost_ms_mean = number(j.at("cost_ms_mean"));
  r.cost_ms_p50 = number(j.at("cost_ms_p50"));
  r.cost_ms_p99 = number(j.at("cost_ms_p99"));
  r.iterations_fpm = j.at("mode_iterations").at("fpm").get<int>();
  r.iterations_som = j.at("mode_iterations").at("som").get<int>();
  r.iterations_eam = j.at("mode_iterations").at("eam").get<int>();
  r.time_bound_s = number(j.at("time_bound_s"));
  r.time_ratio = number(j.at("time_ratio"));
  r.min_clearance_m = number(j.at("min_clearance_m"));
  r.stops = j.at("stops").get<int>();
  r.wall_time_s = number(j.at("wall_time_s"));
  r.error = j.at("error").get<std::string>();
  r.reason = j.value("reason", std::string());
  f.sensor = j.at("sensor").get<std::string>();
  for (int i = 0; i < 3; ++i) f.size_m[i] = j.at("size").at(i).get<double>();
  for (const auto& s : j.at("stop_events")) r.census.stops.push_back(stopFromJson(s));
  r.census.max_calls_without_commit = j.at("max_calls_without_commit").get<int>();
  r.census.longest_no_progress_s = number(j.at("longest_no_progress_s"));
  r.census.longest_no_progress_from_s = number(j.at("longest_no_progress_from_s"));
  r.time_by_mode.time_s = modeSlotsFromJson(j, "time_by_mode_s");
  r.time_by_mode.lost_s = modeSlotsFromJson(j, "time_lost_by_mode_s");
  r.time_by_mode.energy = modeSlotsFromJson(j, "energy_by_mode");
  return r;
}

}  // namespace mmh::bench
