#include "mmh/fpm/fpm_params.hpp"

namespace mmh::fpm {

Params loadParams(const Config& config) {
  Params p;
  p.max_vel_mps = config.getDouble("vehicle.max_vel_mps", 0.1, 50.0);
  p.max_acc_mps2 = config.getDouble("vehicle.max_acc_mps2", 0.1, 50.0);
  p.geofence_min_m = config.getVector3("geofence.min_m", -1e6, 1e6);
  p.geofence_max_m = config.getVector3("geofence.max_m", -1e6, 1e6);
  if ((p.geofence_min_m.array() >= p.geofence_max_m.array()).any())
    throw ConfigError(config.source() + ": geofence.min_m must be below geofence.max_m");
  p.time_weight = config.getDouble("fpm.time_weight", 1e-3, 1e6);
  p.penalty_weight = config.getDouble("fpm.penalty_weight", 1.0, 1e9);
  p.limit_margin_ratio = config.getDouble("fpm.limit_margin_ratio", 0.0, 0.2);
  p.samples_per_piece = config.getInt("fpm.samples_per_piece", 2, 100);
  p.max_evaluations = config.getInt("fpm.max_evaluations", 10, 100000);
  return p;
}

}  // namespace mmh::fpm
