#include "run_flight.hpp"

#include <fstream>
#include <numeric>

#include "mmh/common/forest.hpp"
#include "mmh/sim/ego_forest.hpp"
#include "stack.hpp"
#include "time_by_mode.hpp"

namespace mmh::bench {
namespace {

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const double idx = q * (v.size() - 1);
  const size_t lo = static_cast<size_t>(idx), hi = std::min(v.size() - 1, lo + 1);
  return v[lo] + (v[hi] - v[lo]) * (idx - lo);
}

}  // namespace

FlightResult runFlight(const FlightSpec& spec, const Config& config, double timeout_s,
                       const std::string& paths_dir) {
  FlightResult result;
  result.spec = spec;
  StackOptions options;
  options.config = config;
  options.policy = spec.method;
  options.timeout_s = timeout_s;
  options.sim.world = spec.world;
  options.sim.size_m = spec.size_m;
  options.sim.sensor = spec.sensor;
  options.sim.density_per_m2 = spec.density < 0 ? 0.0 : spec.density;
  options.sim.seed = spec.map_seed;
  options.sim.noise_seed = spec.noise_seed;
  options.sim.start = spec.start;
  options.sim.goal = spec.goal;
  try {
    Stack stack(options);
    const FlightRecord rec = stack.fly();
    const sim::MissionMetrics& m = rec.metrics;
    result.reached = m.reached;
    result.collided = m.collided;
    result.timed_out = rec.end_reason == "timeout";
    result.success = rec.success();
    result.reason = rec.failure_reason;
    result.flight_time_s = m.flight_time_s;
    result.distance_m = m.distance_m;
    result.energy = m.energy;
    std::vector<double> costs;
    for (const PlanCall& c : rec.calls) {
      if (c.mode >= 1 && c.mode <= 3) costs.push_back(c.compute_ms);
    }
    result.iterations = static_cast<int>(costs.size());
    result.iterations_fpm = rec.iterations[1];
    result.iterations_som = rec.iterations[2];
    result.iterations_eam = rec.iterations[3];
    result.cost_ms_mean =
        costs.empty() ? NAN : std::accumulate(costs.begin(), costs.end(), 0.0) / costs.size();
    result.cost_ms_p50 = percentile(costs, 0.5);
    result.cost_ms_p99 = percentile(costs, 0.99);
    result.time_bound_s = m.time_bound_s;
    result.time_ratio = m.time_bound_s > 0 ? m.flight_time_s / m.time_bound_s : NAN;
    result.min_clearance_m = m.min_clearance_m;
    result.stops = rec.stops;
    result.census = rec.census;
    result.time_by_mode = timeByMode(rec.path, config.getDouble("vehicle.max_vel_mps"));
    result.wall_time_s = rec.wall_time_s;
    if (!paths_dir.empty()) {
      nlohmann::json j;
      j["id"] = spec.id();
      j["method"] = spec.method;
      j["density"] = spec.density;
      j["map_index"] = spec.map_index;
      j["trial"] = spec.trial;
      j["success"] = result.success;
      auto& path = j["path"] = nlohmann::json::array();
      for (const PathSample& p : rec.path)
        path.push_back({p.t, p.position.x(), p.position.y(), p.position.z(), p.speed, p.mode});
      auto& obstacles = j["cylinders"] = nlohmann::json::array();
      if (spec.world == "forest") {
        ForestSpec fs;
        fs.size_m = options.sim.size_m;
        fs.density_per_m2 = options.sim.density_per_m2;
        fs.seed = static_cast<uint64_t>(options.sim.seed);
        fs.start = spec.start;
        fs.goal = spec.goal;
        for (const Cylinder& c : generateForest(fs))
          obstacles.push_back({c.center.x(), c.center.y(), c.radius});
      }
      if (spec.world == "ego-forest") {
        // Pillars as their circles; rings as their centre, horizontal semi-axis and yaw.
        sim::EgoForestSpec es;
        es.size_m = options.sim.size_m;
        es.density_per_m2 = options.sim.density_per_m2;
        es.seed = static_cast<uint64_t>(options.sim.seed);
        es.start = spec.start;
        es.goal = spec.goal;
        const sim::EgoForest forest = sim::generateEgoForest(es);
        for (const sim::EgoPillar& p : forest.pillars)
          obstacles.push_back({p.center.x(), p.center.y(), 0.5 * p.diameter_m});
        auto& rings = j["rings"] = nlohmann::json::array();
        for (const sim::EllipticRing& r : forest.rings)
          rings.push_back({r.center.x(), r.center.y(), r.semi_horizontal_m, r.yaw});
      }
      std::ofstream(paths_dir + "/" + spec.id() + ".path.json") << j.dump() << "\n";
    }
  } catch (const std::exception& e) {
    result.error = e.what();
  }
  return result;
}

}  // namespace mmh::bench
