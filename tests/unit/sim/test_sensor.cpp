// Sensor models: field of view, range limits, occlusion, no-return rays, noise and determinism.
#include <gtest/gtest.h>

#include <cmath>

#include "mmh/sim/forest_world.hpp"
#include "mmh/sim/sensor.hpp"

using Eigen::Vector3d;
using mmh::Cylinder;
using mmh::sim::Scan;
using mmh::sim::Sensor;
using mmh::sim::SensorKind;

namespace {

Eigen::Quaterniond yawQ(double deg) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(deg * M_PI / 180.0, Vector3d::UnitZ()));
}

std::vector<Vector3d> points(const Scan& scan, bool returns) {
  std::vector<Vector3d> out;
  const int from = returns ? 0 : scan.num_returns;
  const int to = returns ? scan.num_returns : scan.num_returns + scan.num_no_return;
  for (int i = from; i < to; ++i)
    out.emplace_back(scan.xyz[3 * i], scan.xyz[3 * i + 1], scan.xyz[3 * i + 2]);
  return out;
}

}  // namespace

TEST(DepthCamera, RaysCoverTheFieldOfViewAndNoMore) {
  mmh::sim::SimParams params;
  Sensor cam(SensorKind::kDepth, params, 1);
  ASSERT_EQ(cam.numRays(), 160 * 120);
  double max_az = 0, max_el = 0;
  for (const Vector3d& r : cam.rays()) {
    EXPECT_NEAR(r.norm(), 1.0, 1e-12);
    const double az = std::atan2(r.y(), r.x()) * 180 / M_PI;
    const double el = std::atan2(r.z(), r.x()) * 180 / M_PI;  // on the image plane
    max_az = std::max(max_az, std::abs(az));
    max_el = std::max(max_el, std::abs(el));
  }
  EXPECT_LE(max_az, 40.0);
  EXPECT_GT(max_az, 39.5);  // the corner pixels' centres are just inside the edges
  EXPECT_LE(max_el, 30.0);
  EXPECT_GT(max_el, 29.5);
}

TEST(DepthCamera, SeesOnlyInsideItsFrustumAndRange) {
  // A ring of pillars all around the sensor, some within range and some beyond.
  std::vector<Cylinder> pillars;
  for (int k = 0; k < 36; ++k) {
    const double a = 2 * M_PI * k / 36;
    const double d = (k % 2) ? 3.0 : 6.0;  // 6 m is beyond the 4.5 m range
    pillars.push_back({Eigen::Vector2d(d * std::cos(a), d * std::sin(a)), 0.2, 0.0, 3.0});
  }
  const mmh::sim::ForestWorld world(pillars);
  mmh::sim::SimParams params;
  Sensor cam(SensorKind::kDepth, params, 1);
  Scan scan;
  const Vector3d origin(0, 0, 1.2);
  cam.scan(world, origin, yawQ(90), &scan);  // looking along +y
  ASSERT_GT(scan.num_returns, 0);
  for (const Vector3d& p : points(scan, true)) {
    const Vector3d v = p - origin;
    EXPECT_LE(v.norm(), 4.5 + 1e-6);
    // In the camera frame (x = world y, y = -world x): inside 80 x 60 deg.
    const double az = std::atan2(-v.x(), v.y()) * 180 / M_PI;
    const double el = std::atan2(v.z(), std::hypot(v.x(), v.y())) * 180 / M_PI;
    EXPECT_LE(std::abs(az), 40.0 + 1e-6);
    EXPECT_LE(std::abs(el), 30.0 + 1e-6);
    // Every return lies on a pillar at 3 m.
    EXPECT_NEAR(std::hypot(p.x(), p.y()), 3.0, 0.25);
  }
  // No-return rays are sent 1 m beyond the range.
  ASSERT_GT(scan.num_no_return, 0);
  for (const Vector3d& p : points(scan, false)) EXPECT_NEAR((p - origin).norm(), 5.5, 1e-4);
  EXPECT_EQ(scan.num_returns + scan.num_no_return, cam.numRays());
}

TEST(DepthCamera, APillarBehindAPillarIsNotSeen) {
  const Cylinder front{Eigen::Vector2d(2.0, 0.0), 0.3, 0.0, 3.0};
  const Cylinder back{Eigen::Vector2d(3.5, 0.0), 0.3, 0.0, 3.0};
  const mmh::sim::ForestWorld world({front, back});
  mmh::sim::SimParams params;
  Sensor cam(SensorKind::kDepth, params, 1);
  Scan scan;
  cam.scan(world, Vector3d(0, 0, 1.2), yawQ(0), &scan);
  ASSERT_GT(scan.num_returns, 100);
  for (const Vector3d& p : points(scan, true)) {
    EXPECT_NEAR((p.head<2>() - front.center).norm(), front.radius, 1e-6);
    EXPECT_GT((p.head<2>() - back.center).norm(), back.radius + 0.05);
  }
  // Without the front pillar the back one is seen.
  const mmh::sim::ForestWorld only_back({back});
  cam.scan(only_back, Vector3d(0, 0, 1.2), yawQ(0), &scan);
  EXPECT_GT(scan.num_returns, 100);
}

TEST(Sensor, FreeRayStrideNoiseAndDeterminism) {
  const mmh::sim::ForestWorld world({Cylinder{Eigen::Vector2d(2.0, 0.0), 0.5, 0.0, 3.0}});
  mmh::sim::SimParams params;
  params.free_ray_stride = 4;
  Scan all, some;
  Sensor(SensorKind::kDepth, mmh::sim::SimParams{}, 1)
      .scan(world, Vector3d(0, 0, 1), yawQ(0), &all);
  Sensor(SensorKind::kDepth, params, 1).scan(world, Vector3d(0, 0, 1), yawQ(0), &some);
  EXPECT_EQ(some.num_returns, all.num_returns);
  EXPECT_EQ(some.num_no_return, (all.num_no_return + 3) / 4);
  params.free_ray_stride = 0;
  Sensor(SensorKind::kDepth, params, 1).scan(world, Vector3d(0, 0, 1), yawQ(0), &some);
  EXPECT_EQ(some.num_no_return, 0);

  params = mmh::sim::SimParams{};
  params.depth.range_noise_m = 0.05;
  Scan a, b, c;
  Sensor(SensorKind::kDepth, params, 7).scan(world, Vector3d(0, 0, 1), yawQ(0), &a);
  Sensor(SensorKind::kDepth, params, 7).scan(world, Vector3d(0, 0, 1), yawQ(0), &b);
  Sensor(SensorKind::kDepth, params, 8).scan(world, Vector3d(0, 0, 1), yawQ(0), &c);
  EXPECT_EQ(a.xyz, b.xyz);  // same seed, same noise
  EXPECT_NE(a.xyz, c.xyz);
  EXPECT_NE(a.xyz, all.xyz);
  // The noise has roughly the configured spread.
  double sum2 = 0;
  for (int i = 0; i < a.num_returns; ++i) {
    const double r = Vector3d(a.xyz[3 * i], a.xyz[3 * i + 1], a.xyz[3 * i + 2] - 1).norm();
    const double r0 = Vector3d(all.xyz[3 * i], all.xyz[3 * i + 1], all.xyz[3 * i + 2] - 1).norm();
    sum2 += (r - r0) * (r - r0);
  }
  EXPECT_NEAR(std::sqrt(sum2 / a.num_returns), 0.05, 0.01);
}

TEST(Lidar, CoversAllAzimuthsWithinItsElevationBand) {
  mmh::sim::SimParams params;
  Sensor lidar(SensorKind::kLidar, params, 1);
  EXPECT_EQ(lidar.numRays(), 360 * 56);
  double min_el = 90, max_el = -90;
  for (const Vector3d& r : lidar.rays()) {
    const double el = std::asin(r.z()) * 180 / M_PI;
    min_el = std::min(min_el, el);
    max_el = std::max(max_el, el);
  }
  EXPECT_GE(min_el, -7.0);
  EXPECT_LE(max_el, 52.0);
  // Pillars all around at 4 m are all seen (range 5 m); at 6 m none.
  std::vector<Cylinder> near, far;
  for (int k = 0; k < 8; ++k) {
    const double a = 2 * M_PI * k / 8;
    near.push_back({Eigen::Vector2d(4 * std::cos(a), 4 * std::sin(a)), 0.3, 0, 3});
    far.push_back({Eigen::Vector2d(6 * std::cos(a), 6 * std::sin(a)), 0.3, 0, 3});
  }
  Scan scan;
  lidar.scan(mmh::sim::ForestWorld(near), Vector3d(0, 0, 1.2), yawQ(0), &scan);
  std::vector<int> seen(8, 0);
  for (const Vector3d& p : points(scan, true)) {
    EXPECT_LE((p - Vector3d(0, 0, 1.2)).norm(), 5.0 + 1e-6);
    for (int k = 0; k < 8; ++k)
      if ((p.head<2>() - near[k].center).norm() < 0.31) ++seen[k];
  }
  for (int k = 0; k < 8; ++k) EXPECT_GT(seen[k], 10) << "pillar " << k;
  lidar.scan(mmh::sim::ForestWorld(far), Vector3d(0, 0, 1.2), yawQ(0), &scan);
  EXPECT_EQ(scan.num_returns, 0);
}
