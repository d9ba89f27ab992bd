// The box goals and committed trajectories must stay in (section `geofence`, world frame),
// shared by every service: one loader, one range.
#pragma once

#include <Eigen/Core>
#include <string>

#include "mmh/common/config.hpp"

namespace mmh {

struct Geofence {
  Eigen::Vector3d min_m = Eigen::Vector3d(-30.0, -30.0, 0.3);
  Eigen::Vector3d max_m = Eigen::Vector3d(30.0, 30.0, 2.7);
};

// Throws ConfigError naming the key.
Geofence loadGeofence(const Config& config);

// p inside the axis-aligned box [lo, hi], faces included.
bool insideBox(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

bool insideGeofence(const Geofence& fence, const Eigen::Vector3d& p);

// The box a trajectory from `start` must keep to: the fence, or, for a start outside it by no
// more than tolerance_m on every axis, the fence grown by tolerance_m. The arbiter accepts
// trajectories that leave the fence by up to its arbiter.geofence_tolerance_m, so a vehicle may
// come to rest a little outside; from there a planner must still find the way back in. A start
// farther out keeps the fence (no plan can start there).
Geofence fenceForStart(const Geofence& fence, const Eigen::Vector3d& start, double tolerance_m);

// Empty when p lies inside the fence; else a sentence for the user naming `what` (e.g. "the
// goal"), its coordinates, the axis that is out and the keys geofence.min_m / geofence.max_m.
std::string geofenceViolation(const Geofence& fence, const Eigen::Vector3d& p,
                              const std::string& what);

}  // namespace mmh
