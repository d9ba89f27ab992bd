#include "mmh/sim/simulator.hpp"

#include <cmath>
#include <stdexcept>

#include "mmh/common/forest.hpp"
#include "mmh/common/geofence.hpp"
#include "mmh/sim/ego_forest_world.hpp"
#include "mmh/sim/forest_world.hpp"
#include "mmh/sim/pointcloud_world.hpp"
#include "mmh/sim/world_file.hpp"

namespace mmh::sim {
namespace {

double initialYaw(const SimOptions& o) {
  if (std::isfinite(o.initial_yaw_deg)) return o.initial_yaw_deg * M_PI / 180.0;
  const Eigen::Vector3d d = o.goal - o.start;
  return d.head<2>().norm() > 1e-9 ? std::atan2(d.y(), d.x()) : 0.0;
}

// The options, checked before anything is built on them (the time bound of a goal outside the
// fence would search a space the planners may not fly). A start or goal outside the fence would
// be refused by the arbiter at once and the flight would only time out: say so now.
const SimOptions& checkedOptions(const SimOptions& options, const SimParams& params) {
  if (!options.start.allFinite() || !options.goal.allFinite()) {
    throw std::runtime_error("start and goal must be finite");
  }
  const std::string why =
      startGoalViolation(options.start, options.goal,
                         Geofence{params.geofence_min_m, params.geofence_max_m}, nullptr, "");
  if (!why.empty()) throw std::runtime_error(why);
  if (options.follow != "trajectory" && options.follow != "setpoint") {
    throw std::runtime_error("unknown --follow '" + options.follow +
                             "' (use trajectory or setpoint)");
  }
  return options;
}

// The same for a world with bounds (a PCD world): a start or goal beyond the points in x or y
// flies off the map, where the time bound's search and the planners find nothing to go by.
std::unique_ptr<World> checkedWorld(std::unique_ptr<World> world, const SimOptions& options,
                                    const SimParams& params) {
  if (const auto* cloud = dynamic_cast<const PointCloudWorld*>(world.get())) {
    const WorldBounds bounds{cloud->minCorner(), cloud->maxCorner()};
    const std::string why = startGoalViolation(
        options.start, options.goal, Geofence{params.geofence_min_m, params.geofence_max_m},
        &bounds, options.world);
    if (!why.empty()) throw std::runtime_error(why);
  }
  return world;
}

// The fields both generators' specifications share.
template <class Spec>
Spec specOf(const SimOptions& options) {
  Spec spec;
  spec.size_m = options.size_m;
  spec.density_per_m2 = options.density_per_m2;
  spec.seed = static_cast<uint64_t>(options.seed);
  spec.start = options.start;
  spec.goal = options.goal;
  return spec;
}

}  // namespace

SensorKind parseSensorKind(const std::string& name) {
  if (name == "depth") return SensorKind::kDepth;
  if (name == "lidar") return SensorKind::kLidar;
  throw std::runtime_error("unknown sensor '" + name + "' (use depth or lidar)");
}

ForestSpec forestSpecOf(const SimOptions& options) {
  return specOf<ForestSpec>(options);
}

EgoForestSpec egoForestSpecOf(const SimOptions& options) {
  return specOf<EgoForestSpec>(options);
}

std::unique_ptr<World> makeWorld(const SimOptions& options, const SimParams& params) {
  if (options.world == "forest") {
    try {
      return std::make_unique<ForestWorld>(generateForest(forestSpecOf(options)));
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(e.what());
    }
  }
  if (options.world == "ego-forest") {
    EgoForestBoundOptions bound;
    bound.grid_m = params.bound_grid_m;
    bound.min_m = params.geofence_min_m;
    bound.max_m = params.geofence_max_m;
    try {
      return std::make_unique<EgoForestWorld>(generateEgoForest(egoForestSpecOf(options)), bound);
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(e.what());
    }
  }
  if (isPcdWorld(options.world)) {
    PointCloudWorldOptions o;
    o.voxel_m = params.pcd_voxel_m;
    o.bound_grid_m = params.bound_grid_m;
    o.bound_min_m = params.geofence_min_m;
    o.bound_max_m = params.geofence_max_m;
    return PointCloudWorld::loadPcd(options.world, o);
  }
  throw std::runtime_error("unknown world '" + options.world +
                           "' (use forest, ego-forest or the path of a .pcd file)");
}

Simulator::Simulator(const SimParams& params, const SimOptions& options)
    : Simulator(params, options, makeWorld(checkedOptions(options, params), params)) {}

Simulator::Simulator(const SimParams& params, const SimOptions& options,
                     std::unique_ptr<World> world)
    : params_(params),
      options_(checkedOptions(options, params)),
      world_(checkedWorld(std::move(world), options_, params_)),
      step_us_(std::max<int64_t>(1, std::llround(params.step_s * 1e6))),
      vehicle_(options.start, initialYaw(options), options.start_utime, params),
      sensor_(parseSensorKind(options.sensor), params, static_cast<uint64_t>(options.noise_seed)),
      monitor_(*world_, params, options.start, options.goal) {
  if (world_->clearance(options.start) < params.vehicle_radius_m) {
    throw std::runtime_error("the start lies inside an obstacle (or closer than vehicle.radius_m)");
  }
  if (options.follow == "setpoint") vehicle_.followSetpoints();
}

Simulator::StepResult Simulator::step() {
  StepResult result;
  const int64_t now = vehicle_.nowUtime() + step_us_;
  flown_.clear();
  vehicle_.advance(now, &flown_);
  result.event = monitor_.update(now, vehicle_, flown_);
  // Frames and status messages on their own rates, on the step grid, without drift.
  const int64_t elapsed = now - options_.start_utime;
  const auto due = [&](int64_t count, double rate_hz) {
    return elapsed >= std::llround(static_cast<double>(count) * 1e6 / rate_hz);
  };
  if (due(scans_done_, params_.pointcloud_rate_hz)) {
    while (due(scans_done_, params_.pointcloud_rate_hz)) ++scans_done_;
    sensor_.scan(*world_, vehicle_.state().position, vehicle_.orientation(), &scan_);
    result.scan = true;
  }
  if (due(statuses_done_, params_.mission_status_rate_hz) || result.event) {
    while (due(statuses_done_, params_.mission_status_rate_hz)) ++statuses_done_;
    result.status = true;
  }
  return result;
}

bool Simulator::finished() const {
  const MissionMetrics& m = monitor_.metrics();
  return m.reached || (m.collided && params_.stop_on_collision);
}

}  // namespace mmh::sim
