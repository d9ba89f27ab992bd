// Ray-casting range sensors: the forward depth camera (pinhole, 80 x 60 deg, 4.5 m) and the 360 deg
// LiDAR (MID-360-like, -7..52 deg, 5 m). Rays are cast against the World with occlusion (the first
// surface stops a ray), optional Gaussian range noise is added, and the scan is expressed as
// world-frame points, with "no-return" rays placed beyond the range (see
// lcmtypes/pointcloud_t.lcm).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <random>
#include <vector>

#include "mmh/sim/sim_params.hpp"
#include "mmh/sim/world.hpp"

namespace mmh::sim {

enum class SensorKind { kDepth = 1, kLidar = 2 };

// A no-return ray is sent as a point this far beyond the sensor range.
constexpr double kNoReturnExtra_m = 1.0;

struct Scan {
  SensorKind kind = SensorKind::kDepth;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();               // sensor, world frame
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // sensor to world
  double max_range_m = 0.0;
  std::vector<float> xyz;  // world frame: the returns first, then the no-return points
  int num_returns = 0;
  int num_no_return = 0;  // no-return points included (every free_ray_stride-th)
};

class Sensor {
 public:
  // Sensor frame: x forward, y left, z up (the vehicle's body frame; the sensor sits at its
  // centre).
  Sensor(SensorKind kind, const SimParams& params, uint64_t noise_seed);

  SensorKind kind() const { return kind_; }
  double maxRange() const { return range_; }
  int numRays() const { return static_cast<int>(rays_.size()); }
  const std::vector<Eigen::Vector3d>& rays() const { return rays_; }  // unit, sensor frame

  void scan(const World& world, const Eigen::Vector3d& position,
            const Eigen::Quaterniond& orientation, Scan* out);

 private:
  SensorKind kind_;
  double range_ = 0.0, noise_ = 0.0;
  int free_ray_stride_ = 1;
  std::vector<Eigen::Vector3d> rays_;
  std::vector<Eigen::Vector3d> world_rays_;  // scratch
  std::vector<double> ranges_;               // scratch
  std::mt19937_64 rng_;
};

}  // namespace mmh::sim
