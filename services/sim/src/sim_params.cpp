#include "mmh/sim/sim_params.hpp"

namespace mmh::sim {

SimParams loadSimParams(const Config& c) {
  SimParams p;
  p.step_s = c.getDouble("sim.step_s", 1e-4, 0.1);
  p.pointcloud_rate_hz = c.getDouble("sim.pointcloud_rate_hz", 0.1, 100.0);
  p.mission_status_rate_hz = c.getDouble("sim.mission_status_rate_hz", 0.1, 100.0);
  p.goal_tolerance_m = c.getDouble("sim.goal_tolerance_m", 0.01, 10.0);
  p.stop_on_collision = c.getBool("sim.stop_on_collision");
  p.max_yaw_rate_dps = c.getDouble("sim.max_yaw_rate_dps", 1.0, 3600.0);
  p.yaw_time_constant_s = c.getDouble("sim.yaw_time_constant_s", 0.0, 10.0);
  p.yaw_lookahead_s = c.getDouble("sim.yaw_lookahead_s", 0.01, 10.0);
  p.free_ray_stride = c.getInt("sim.free_ray_stride", 0, 1000);
  p.depth.width_px = c.getInt("sim.depth.width_px", 2, 4096);
  p.depth.height_px = c.getInt("sim.depth.height_px", 2, 4096);
  p.depth.hfov_deg = c.getDouble("sim.depth.hfov_deg", 1.0, 170.0);
  p.depth.vfov_deg = c.getDouble("sim.depth.vfov_deg", 1.0, 170.0);
  p.depth.range_m = c.getDouble("sim.depth.range_m", 0.1, 100.0);
  p.depth.range_noise_m = c.getDouble("sim.depth.range_noise_m", 0.0, 1.0);
  p.lidar.horizontal_rays = c.getInt("sim.lidar.horizontal_rays", 1, 10000);
  p.lidar.vertical_rays = c.getInt("sim.lidar.vertical_rays", 1, 1000);
  p.lidar.vmin_deg = c.getDouble("sim.lidar.vmin_deg", -90.0, 90.0);
  p.lidar.vmax_deg = c.getDouble("sim.lidar.vmax_deg", p.lidar.vmin_deg, 90.0);
  p.lidar.range_m = c.getDouble("sim.lidar.range_m", 0.1, 200.0);
  p.lidar.range_noise_m = c.getDouble("sim.lidar.range_noise_m", 0.0, 1.0);
  p.pcd_voxel_m = c.getDouble("sim.pcd_voxel_m", 0.005, 1.0);
  p.bound_grid_m = c.getDouble("sim.bound_grid_m", 0.02, 1.0);
  p.vehicle_radius_m = c.getDouble("vehicle.radius_m", 0.01, 5.0);
  p.max_vel_mps = c.getDouble("vehicle.max_vel_mps", 0.1, 50.0);
  p.max_acc_mps2 = c.getDouble("vehicle.max_acc_mps2", 0.1, 100.0);
  p.geofence_min_m = c.getVector3("geofence.min_m", -1e5, 1e5);
  p.geofence_max_m = c.getVector3("geofence.max_m", -1e5, 1e5);
  return p;
}

}  // namespace mmh::sim
