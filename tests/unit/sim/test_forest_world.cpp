// Ray casting against forest cylinders: analytic cases, the binned batch against brute force,
// and the generator properties the simulator relies on.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mmh/sim/forest_world.hpp"

using Eigen::Vector3d;
using mmh::Cylinder;

TEST(RayCylinder, AnalyticCases) {
  const Cylinder c{Eigen::Vector2d(0, 0), 1.0, 0.0, 3.0};
  EXPECT_NEAR(mmh::sim::rayCylinder(Vector3d(-5, 0, 1), Vector3d(1, 0, 0), c), 4.0, 1e-12);
  // Oblique: enters the side at x = -1 after 4 m in x.
  const Vector3d d = Vector3d(1, 0, 0.25).normalized();
  EXPECT_NEAR(mmh::sim::rayCylinder(Vector3d(-5, 0, 1), d, c), 4.0 / d.x(), 1e-12);
  // Misses beside, passes over the top, hits the top cap from above.
  EXPECT_LT(mmh::sim::rayCylinder(Vector3d(-5, 1.5, 1), Vector3d(1, 0, 0), c), 0.0);
  EXPECT_LT(mmh::sim::rayCylinder(Vector3d(-5, 0, 3.5), Vector3d(1, 0, 0), c), 0.0);
  EXPECT_NEAR(mmh::sim::rayCylinder(Vector3d(0.2, 0, 5), Vector3d(0, 0, -1), c), 2.0, 1e-12);
  // Behind the origin, and from inside.
  EXPECT_LT(mmh::sim::rayCylinder(Vector3d(-5, 0, 1), Vector3d(-1, 0, 0), c), 0.0);
  EXPECT_EQ(mmh::sim::rayCylinder(Vector3d(0.5, 0, 1), Vector3d(1, 0, 0), c), 0.0);
}

TEST(ForestWorld, BatchRaycastEqualsBruteForce) {
  mmh::ForestSpec spec;
  spec.density_per_m2 = 0.2;
  spec.seed = 11;
  const mmh::sim::ForestWorld world = mmh::sim::ForestWorld::generate(spec);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int pose = 0; pose < 20; ++pose) {
    const Vector3d origin(20 * u(rng), 20 * u(rng), 1.2);
    if (world.clearance(origin) < 0.2) continue;
    std::vector<Vector3d> dirs;
    for (int i = 0; i < 2000; ++i)
      dirs.push_back(Vector3d(u(rng), u(rng), 0.5 * u(rng)).normalized());
    dirs.push_back(Vector3d(0, 0, 1));  // straight up
    std::vector<double> ranges;
    world.raycast(origin, dirs, 5.0, &ranges);
    for (size_t i = 0; i < dirs.size(); ++i) {
      double best = -1.0;
      for (const Cylinder& c : world.cylinders()) {
        const double t = mmh::sim::rayCylinder(origin, dirs[i], c);
        if (t >= 0.0 && t <= 5.0 && (best < 0.0 || t < best)) best = t;
      }
      ASSERT_NEAR(ranges[i], best, 1e-9) << "pose " << pose << " ray " << i;
    }
  }
}

TEST(ForestWorld, ClearanceAndGeneratorDensityClearanceDeterminism) {
  for (double density : {0.0, 0.05, 0.1, 0.2}) {
    mmh::ForestSpec spec;
    spec.density_per_m2 = density;
    spec.seed = 3;
    const mmh::sim::ForestWorld world = mmh::sim::ForestWorld::generate(spec);
    // Exact count: density x area.
    EXPECT_EQ(world.cylinders().size(), static_cast<size_t>(std::lround(density * 2500.0)));
    // Start and goal at least 2 m from every surface; full height; diameters in range.
    EXPECT_GE(world.clearance(spec.start), 2.0);
    EXPECT_GE(world.clearance(spec.goal), 2.0);
    for (const Cylinder& c : world.cylinders()) {
      EXPECT_GE(2 * c.radius, 0.25 - 1e-12);
      EXPECT_LE(2 * c.radius, 1.05 + 1e-12);
      EXPECT_EQ(c.z_min, 0.0);
      EXPECT_EQ(c.z_max, 3.0);
    }
    // Same seed, same world.
    const mmh::sim::ForestWorld again = mmh::sim::ForestWorld::generate(spec);
    ASSERT_EQ(again.cylinders().size(), world.cylinders().size());
    for (size_t i = 0; i < world.cylinders().size(); ++i) {
      EXPECT_EQ(again.cylinders()[i].center, world.cylinders()[i].center);
      EXPECT_EQ(again.cylinders()[i].radius, world.cylinders()[i].radius);
    }
  }
  const mmh::sim::ForestWorld one({Cylinder{Eigen::Vector2d(1, 0), 0.5, 0, 3}});
  EXPECT_NEAR(one.clearance(Vector3d(-1, 0, 1)), 1.5, 1e-12);
  EXPECT_TRUE(std::isinf(mmh::sim::ForestWorld({}).clearance(Vector3d::Zero())));
  // Above the top, beside the rim, inside.
  EXPECT_NEAR(one.clearance(Vector3d(1, 0, 3.4)), 0.4, 1e-12);
  EXPECT_NEAR(one.clearance(Vector3d(1.8, 0, 3.4)), 0.5, 1e-12);
  EXPECT_NEAR(one.clearance(Vector3d(1.1, 0, 1.0)), -0.4, 1e-12);
  EXPECT_NEAR(one.clearance(Vector3d(1.0, 0, 2.9)), -0.1, 1e-12);
}
