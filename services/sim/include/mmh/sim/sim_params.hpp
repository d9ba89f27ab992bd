// Parameters of the simulator (section `sim` of the configuration, plus the shared vehicle and
// geofence keys), read and range-checked at start-up so that a bad file names the key.
#pragma once

#include <Eigen/Core>

#include "mmh/common/config.hpp"
#include "mmh/sim/tracking_model.hpp"

namespace mmh::sim {

// One ray-casting sensor. The depth camera is a pinhole of width x height rays over hfov x vfov;
// the LiDAR has horizontal_rays over 360 deg and vertical_rays between vmin_deg and vmax_deg.
struct DepthCameraParams {
  int width_px = 160;
  int height_px = 120;
  double hfov_deg = 80.0;
  double vfov_deg = 60.0;
  double range_m = 4.5;
  double range_noise_m = 0.0;  // standard deviation of Gaussian range noise on returns
};

struct LidarParams {
  int horizontal_rays = 360;
  int vertical_rays = 56;
  double vmin_deg = -7.0;
  double vmax_deg = 52.0;
  double range_m = 5.0;
  double range_noise_m = 0.0;
};

struct SimParams {
  double step_s = 0.01;              // physics step; ODOMETRY every step
  double pointcloud_rate_hz = 15.0;  // sensor frames per second of simulated time
  double mission_status_rate_hz = 10.0;
  double goal_tolerance_m = 0.3;  // reached = centre within this distance of the goal
  // arbiter.goal_relocate_radius_m: how far from the goal sent a goal moved by the arbiter may
  // be and still count (MissionMonitor::acceptMovedGoal).
  double goal_relocate_radius_m = 1.5;
  bool stop_on_collision = true;  // finished() once the vehicle touched an obstacle
  // Yaw follows the direction of flight: the direction to the point yaw_lookahead_s ahead on the
  // trajectory (or a later one yaw_lookahead_min_m away), through a first-order lag with
  // yaw_time_constant_s, limited to max_yaw_rate_dps.
  double max_yaw_rate_dps = 120.0;
  double yaw_time_constant_s = 0.2;
  double yaw_lookahead_s = 0.5;
  double yaw_lookahead_min_m = 0.2;
  // No-return rays: every free_ray_stride-th ray that hit nothing is sent as a point beyond the
  // sensor range (0 = none), so that the mapping clears free space along it.
  int free_ray_stride = 1;
  DepthCameraParams depth;
  LidarParams lidar;
  double pcd_voxel_m = 0.05;  // PCD worlds are voxelised at this edge for ray casting
  double bound_grid_m = 0.1;  // grid of the A* that bounds the shortest path in PCD worlds
  TrackingParams tracking;    // mmh-sim --follow setpoint: the flight controller's loop
  // A mission waypoint with its stop flag is arrived at only below this speed (mission.*).
  double mission_stop_speed_mps = 0.2;
  // Shared keys.
  double vehicle_radius_m = 0.15;
  double max_vel_mps = 3.0;
  double max_acc_mps2 = 2.0;
  Eigen::Vector3d geofence_min_m = Eigen::Vector3d(-30.0, -30.0, 0.3);
  Eigen::Vector3d geofence_max_m = Eigen::Vector3d(30.0, 30.0, 2.7);
};

// Reads every key above from `config` (all are required; deploy/config/default.yaml lists them).
// Throws ConfigError naming the key when one is missing or out of range.
SimParams loadSimParams(const Config& config);

}  // namespace mmh::sim
