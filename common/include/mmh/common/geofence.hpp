// The box goals and committed trajectories must stay in (section `geofence`, world frame),
// shared by every service: one loader, one range.
#pragma once

#include <Eigen/Core>

#include "mmh/common/config.hpp"

namespace mmh {

struct Geofence {
  Eigen::Vector3d min_m = Eigen::Vector3d(-30.0, -30.0, 0.3);
  Eigen::Vector3d max_m = Eigen::Vector3d(30.0, 30.0, 2.7);
};

// Throws ConfigError naming the key.
Geofence loadGeofence(const Config& config);

}  // namespace mmh
