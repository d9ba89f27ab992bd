#include "mmh/sim/sensor.hpp"

#include <algorithm>
#include <cmath>

namespace mmh::sim {
namespace {

double deg2rad(double d) {
  return d * M_PI / 180.0;
}

}  // namespace

Sensor::Sensor(SensorKind kind, const SimParams& params, uint64_t noise_seed)
    : kind_(kind), free_ray_stride_(params.free_ray_stride), rng_(noise_seed) {
  if (kind == SensorKind::kDepth) {
    const DepthCameraParams& d = params.depth;
    range_ = d.range_m;
    noise_ = d.range_noise_m;
    // Pinhole: pixel centres on the image plane x = 1, focal lengths from the fields of view.
    const double fx = 0.5 * d.width_px / std::tan(0.5 * deg2rad(d.hfov_deg));
    const double fy = 0.5 * d.height_px / std::tan(0.5 * deg2rad(d.vfov_deg));
    rays_.reserve(static_cast<size_t>(d.width_px) * d.height_px);
    for (int v = 0; v < d.height_px; ++v) {
      for (int u = 0; u < d.width_px; ++u) {
        const double y = -(u + 0.5 - 0.5 * d.width_px) / fx;
        const double z = -(v + 0.5 - 0.5 * d.height_px) / fy;
        rays_.push_back(Eigen::Vector3d(1.0, y, z).normalized());
      }
    }
  } else {
    const LidarParams& l = params.lidar;
    range_ = l.range_m;
    noise_ = l.range_noise_m;
    rays_.reserve(static_cast<size_t>(l.horizontal_rays) * l.vertical_rays);
    for (int j = 0; j < l.vertical_rays; ++j) {
      const double el =
          deg2rad(l.vmin_deg + (j + 0.5) * (l.vmax_deg - l.vmin_deg) / l.vertical_rays);
      for (int k = 0; k < l.horizontal_rays; ++k) {
        const double az = 2.0 * M_PI * k / l.horizontal_rays;
        rays_.emplace_back(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
      }
    }
  }
}

void Sensor::scan(const World& world, const Eigen::Vector3d& position,
                  const Eigen::Quaterniond& orientation, Scan* out) {
  out->kind = kind_;
  out->position = position;
  out->orientation = orientation;
  out->max_range_m = range_;
  out->xyz.clear();
  out->num_returns = 0;
  out->num_no_return = 0;
  const Eigen::Matrix3d rot = orientation.toRotationMatrix();
  world_rays_.resize(rays_.size());
  for (size_t i = 0; i < rays_.size(); ++i) world_rays_[i] = rot * rays_[i];
  world.raycast(position, world_rays_, range_, &ranges_);
  out->xyz.reserve(3 * rays_.size());
  std::normal_distribution<double> noise(0.0, noise_ > 0.0 ? noise_ : 1.0);
  std::vector<size_t> misses;
  for (size_t i = 0; i < rays_.size(); ++i) {
    double r = ranges_[i];
    if (r < 0.0) {
      misses.push_back(i);
      continue;
    }
    // Noise never turns a return into a no-return: a receiver must still see an obstacle.
    if (noise_ > 0.0) r = std::clamp(r + noise(rng_), 0.0, range_);
    const Eigen::Vector3d p = position + r * world_rays_[i];
    out->xyz.insert(out->xyz.end(), {static_cast<float>(p.x()), static_cast<float>(p.y()),
                                     static_cast<float>(p.z())});
    ++out->num_returns;
  }
  if (free_ray_stride_ > 0) {
    const double r = range_ + kNoReturnExtra_m;
    for (size_t k = 0; k < misses.size(); k += free_ray_stride_) {
      const Eigen::Vector3d p = position + r * world_rays_[misses[k]];
      out->xyz.insert(out->xyz.end(), {static_cast<float>(p.x()), static_cast<float>(p.y()),
                                       static_cast<float>(p.z())});
      ++out->num_no_return;
    }
  }
}

}  // namespace mmh::sim
