#include "mmh/fpm/fpm_params.hpp"

#include "mmh/common/config_constraints.hpp"
#include "mmh/common/geofence.hpp"
#include "mmh/common/vehicle_limits.hpp"

namespace mmh::fpm {

Params loadParams(const Config& config) {
  Params p;
  const VehicleLimits vehicle = loadVehicleLimits(config);
  p.max_vel_mps = vehicle.max_vel_mps;
  p.max_acc_mps2 = vehicle.max_acc_mps2;
  const Geofence geofence = loadGeofence(config);
  p.geofence_min_m = geofence.min_m;
  p.geofence_max_m = geofence.max_m;
  p.time_weight = config.getDouble("fpm.time_weight");
  p.penalty_weight = config.getDouble("fpm.penalty_weight");
  p.limit_margin_ratio = config.getDouble("fpm.limit_margin_ratio");
  p.samples_per_piece = config.getInt("fpm.samples_per_piece");
  p.max_evaluations = config.getInt("fpm.max_evaluations");
  checkConfigConstraints(config);
  return p;
}

}  // namespace mmh::fpm
