#include "mmh/sim/sim_params.hpp"

#include "mmh/common/config_constraints.hpp"
#include "mmh/common/geofence.hpp"
#include "mmh/common/mission.hpp"
#include "mmh/common/vehicle_limits.hpp"

namespace mmh::sim {

SimParams loadSimParams(const Config& c) {
  SimParams p;
  p.step_s = c.getDouble("sim.step_s");
  p.pointcloud_rate_hz = c.getDouble("sim.pointcloud_rate_hz");
  p.mission_status_rate_hz = c.getDouble("sim.mission_status_rate_hz");
  p.goal_tolerance_m = c.getDouble("sim.goal_tolerance_m");
  p.goal_relocate_radius_m = c.getDouble("arbiter.goal_relocate_radius_m");
  p.stop_on_collision = c.getBool("sim.stop_on_collision");
  p.max_yaw_rate_dps = c.getDouble("sim.max_yaw_rate_dps");
  p.yaw_time_constant_s = c.getDouble("sim.yaw_time_constant_s");
  p.yaw_lookahead_s = c.getDouble("sim.yaw_lookahead_s");
  p.yaw_lookahead_min_m = c.getDouble("sim.yaw_lookahead_min_m");
  p.free_ray_stride = c.getInt("sim.free_ray_stride");
  p.depth.width_px = c.getInt("sim.depth.width_px");
  p.depth.height_px = c.getInt("sim.depth.height_px");
  p.depth.hfov_deg = c.getDouble("sim.depth.hfov_deg");
  p.depth.vfov_deg = c.getDouble("sim.depth.vfov_deg");
  p.depth.range_m = c.getDouble("sim.depth.range_m");
  p.depth.range_noise_m = c.getDouble("sim.depth.range_noise_m");
  p.lidar.horizontal_rays = c.getInt("sim.lidar.horizontal_rays");
  p.lidar.vertical_rays = c.getInt("sim.lidar.vertical_rays");
  p.lidar.vmin_deg = c.getDouble("sim.lidar.vmin_deg");
  p.lidar.vmax_deg = c.getDouble("sim.lidar.vmax_deg");
  p.lidar.range_m = c.getDouble("sim.lidar.range_m");
  p.lidar.range_noise_m = c.getDouble("sim.lidar.range_noise_m");
  p.pcd_voxel_m = c.getDouble("sim.pcd_voxel_m");
  p.bound_grid_m = c.getDouble("sim.bound_grid_m");
  p.tracking.bandwidth_hz = c.getDouble("sim.tracking.bandwidth_hz");
  p.tracking.damping_ratio = c.getDouble("sim.tracking.damping_ratio");
  p.tracking.max_acc_mps2 = c.getDouble("sim.tracking.max_acc_mps2");
  p.tracking.setpoint_timeout_s = c.getDouble("sim.tracking.setpoint_timeout_s");
  p.mission_stop_speed_mps = loadMissionRules(c).stop_speed_mps;
  p.vehicle_radius_m = c.getDouble("vehicle.radius_m");
  const VehicleLimits vehicle = loadVehicleLimits(c);
  p.max_vel_mps = vehicle.max_vel_mps;
  p.max_acc_mps2 = vehicle.max_acc_mps2;
  const Geofence geofence = loadGeofence(c);
  p.geofence_min_m = geofence.min_m;
  p.geofence_max_m = geofence.max_m;
  checkConfigConstraints(c);  // among them: lidar.vmax_deg >= lidar.vmin_deg
  return p;
}

}  // namespace mmh::sim
