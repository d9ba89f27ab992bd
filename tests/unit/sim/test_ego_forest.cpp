// The EGO-Planner / Fast-Planner random forest: the generator's invariants (sizes, spacing,
// start and goal clear, determinism, ring geometry), the exact distance and ray casting against
// hand-made obstacles and brute force, and the world inside the simulator.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mmh/sim/ego_forest_world.hpp"
#include "mmh/sim/sensor.hpp"
#include "mmh/sim/simulator.hpp"

using Eigen::Vector2d;
using Eigen::Vector3d;
using mmh::sim::EgoColumn;
using mmh::sim::EgoForest;
using mmh::sim::EgoForestSpec;
using mmh::sim::EgoPillar;
using mmh::sim::EllipticRing;
using mmh::sim::kEgoColumnEdgeM;

namespace {

EgoForestSpec protocolSpec(double density, uint64_t seed) {
  EgoForestSpec spec;
  spec.density_per_m2 = density;
  spec.seed = seed;
  return spec;
}

Vector2d columnCenter(const EgoColumn& c) {
  return Vector2d((c.ix + 0.5) * kEgoColumnEdgeM, (c.iy + 0.5) * kEgoColumnEdgeM);
}

// Distance in xy from p to the column's square.
double squareDistance(const Vector2d& p, const EgoColumn& c) {
  const Vector2d lo(c.ix * kEgoColumnEdgeM, c.iy * kEgoColumnEdgeM);
  const Vector2d hi = lo + Vector2d::Constant(kEgoColumnEdgeM);
  return (p - p.cwiseMax(lo).cwiseMin(hi)).norm();
}

// One pillar of one column and one ring, for known answers.
EgoForest handMadeForest() {
  EgoForest f;
  EgoPillar pillar;
  pillar.center = Vector2d(0.05, 0.05);
  pillar.diameter_m = 0.1;
  pillar.columns.push_back(EgoColumn{0, 0, 2.0});  // the box [0, 0.1]^2 x [0, 2]
  f.pillars.push_back(pillar);
  EllipticRing ring;
  ring.center = Vector3d(5.0, 0.0, 1.25);
  ring.yaw = 0.0;  // in the plane x = 5
  ring.semi_horizontal_m = 0.6;
  ring.semi_vertical_m = 1.0;
  ring.tube_radius_m = 0.05;
  f.rings.push_back(ring);
  return f;
}

}  // namespace

TEST(EgoForest, CountsFollowTheDensityWithOneRingPer15Pillars) {
  EgoForestSpec spec = protocolSpec(0.1875, 3);
  spec.size_m = Vector3d(40, 20, 3);  // Fast-Planner's default: 150 pillars and 10 rings
  spec.start = Vector3d(-18, 0, 1.2);
  spec.goal = Vector3d(18, 0, 1.2);
  const EgoForest f = mmh::sim::generateEgoForest(spec);
  EXPECT_EQ(f.pillars.size(), 150u);
  EXPECT_EQ(f.rings.size(), 10u);
}

TEST(EgoForest, PillarsHaveTheirDiametersAndRaggedHeights) {
  const EgoForest f = mmh::sim::generateEgoForest(protocolSpec(0.2, 11));
  ASSERT_EQ(f.pillars.size(), 500u);
  bool ragged = false;
  for (const EgoPillar& p : f.pillars) {
    EXPECT_GE(p.diameter_m, 0.25);
    EXPECT_LE(p.diameter_m, 1.05);
    ASSERT_FALSE(p.columns.empty());
    double h_min = 1e9, h_max = -1e9, extent = 0.0;
    for (const EgoColumn& c : p.columns) {
      EXPECT_GE(c.height_m, 0.0);
      EXPECT_LE(c.height_m, 3.0);
      h_min = std::min(h_min, c.height_m);
      h_max = std::max(h_max, c.height_m);
      // Every column centre inside the pillar's circle; the footprint spans about the diameter.
      const double r = (columnCenter(c) - p.center).norm();
      EXPECT_LE(r, 0.5 * p.diameter_m + 1e-9);
      extent = std::max(extent, r);
    }
    EXPECT_GT(2.0 * extent + kEgoColumnEdgeM, p.diameter_m - 2.0 * kEgoColumnEdgeM);
    if (p.columns.size() > 4 && h_max - h_min > 1.0) ragged = true;
  }
  EXPECT_TRUE(ragged) << "columns of a pillar should have their own heights";
}

TEST(EgoForest, CentresAreSpacedAndStartAndGoalClear) {
  const EgoForestSpec spec = protocolSpec(0.5, 5);  // the densest the benchmark flies
  const EgoForest f = mmh::sim::generateEgoForest(spec);
  std::vector<Vector2d> centres;
  for (const EgoPillar& p : f.pillars) centres.push_back(p.center);
  for (const EllipticRing& r : f.rings) centres.push_back(r.center.head<2>());
  for (size_t i = 0; i < centres.size(); ++i)
    for (size_t j = i + 1; j < centres.size(); ++j)
      ASSERT_GE((centres[i] - centres[j]).norm(), 0.8 - 1e-9) << i << " " << j;
  for (const Vector3d& end : {spec.start, spec.goal}) {
    for (const EgoPillar& p : f.pillars)
      for (const EgoColumn& c : p.columns) ASSERT_GE(squareDistance(end.head<2>(), c), 2.0);
    for (const EllipticRing& r : f.rings) {
      // The ring's footprint is a segment of half-length semi_horizontal + tube.
      EXPECT_GE((r.center.head<2>() - end.head<2>()).norm() - r.semi_horizontal_m - r.tube_radius_m,
                2.0);
    }
  }
  const mmh::sim::EgoForestWorld world(f, {});
  EXPECT_GE(world.clearance(spec.start), 2.0);
  EXPECT_GE(world.clearance(spec.goal), 2.0);
}

TEST(EgoForest, RingsHaveTheirGeometry) {
  const EgoForest f = mmh::sim::generateEgoForest(protocolSpec(0.3, 8));
  ASSERT_EQ(f.rings.size(), 50u);  // 750 pillars / 15
  for (const EllipticRing& r : f.rings) {
    EXPECT_GE(r.semi_horizontal_m, 0.5);
    EXPECT_LE(r.semi_horizontal_m, 0.7);
    EXPECT_GE(r.semi_vertical_m, 0.7);
    EXPECT_LE(r.semi_vertical_m, 1.2);
    EXPECT_GE(r.center.z(), 1.2);
    EXPECT_LE(r.center.z(), 1.3);
    EXPECT_LE(std::abs(r.yaw), 0.5);
    EXPECT_DOUBLE_EQ(r.tube_radius_m, 0.05);
  }
}

TEST(EgoForest, SameSeedSameWorldOtherSeedOtherWorld) {
  const EgoForest a = mmh::sim::generateEgoForest(protocolSpec(0.2, 21));
  const EgoForest b = mmh::sim::generateEgoForest(protocolSpec(0.2, 21));
  const EgoForest c = mmh::sim::generateEgoForest(protocolSpec(0.2, 22));
  ASSERT_EQ(a.pillars.size(), b.pillars.size());
  ASSERT_EQ(a.rings.size(), b.rings.size());
  for (size_t i = 0; i < a.pillars.size(); ++i) {
    EXPECT_EQ(a.pillars[i].center, b.pillars[i].center);
    ASSERT_EQ(a.pillars[i].columns.size(), b.pillars[i].columns.size());
    for (size_t k = 0; k < a.pillars[i].columns.size(); ++k)
      EXPECT_EQ(a.pillars[i].columns[k].height_m, b.pillars[i].columns[k].height_m);
  }
  for (size_t i = 0; i < a.rings.size(); ++i) EXPECT_EQ(a.rings[i].center, b.rings[i].center);
  EXPECT_NE(a.pillars[0].center, c.pillars[0].center);
}

TEST(EgoForest, ImpossibleSpecsAreErrors) {
  EXPECT_THROW(mmh::sim::generateEgoForest(protocolSpec(-0.1, 1)), std::invalid_argument);
  EgoForestSpec crowded = protocolSpec(3.0, 1);  // 75 pillars 0.8 m apart in 5 m x 5 m
  crowded.size_m = Vector3d(5, 5, 3);
  EXPECT_THROW(mmh::sim::generateEgoForest(crowded), std::invalid_argument);
}

TEST(EllipticRing, DistanceToTheCurveEqualsDenseSampling) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (const auto& [a, b] : {std::pair{0.6, 1.0}, std::pair{1.2, 0.7}, std::pair{0.5, 0.5}}) {
    for (int i = 0; i < 200; ++i) {
      const double x = u(rng), y = u(rng);
      double brute = 1e9;
      for (int k = 0; k < 20000; ++k) {
        const double th = 2.0 * M_PI * k / 20000;
        brute = std::min(brute, std::hypot(x - a * std::cos(th), y - b * std::sin(th)));
      }
      EXPECT_NEAR(mmh::sim::distanceToEllipseCurve(a, b, x, y), brute, 2e-4) << x << " " << y;
    }
  }
  // On the axes: the nearer vertex (inside the evolute the foot point leaves the axis).
  EXPECT_NEAR(mmh::sim::distanceToEllipseCurve(0.6, 1.0, 0.0, 0.0), 0.6, 1e-12);
  EXPECT_NEAR(mmh::sim::distanceToEllipseCurve(0.6, 1.0, 0.0, 0.8), 0.2, 1e-12);
  EXPECT_NEAR(mmh::sim::distanceToEllipseCurve(0.6, 1.0, 0.0, 1.5), 0.5, 1e-12);
}

TEST(EgoForestWorld, ClearanceAtKnownPoints) {
  const mmh::sim::EgoForestWorld world(handMadeForest(), {});
  // The column [0, 0.1]^2 x [0, 2]: beside, above, diagonal to its top edge, inside.
  EXPECT_NEAR(world.clearance(Vector3d(0.4, 0.05, 1.0)), 0.3, 1e-12);
  EXPECT_NEAR(world.clearance(Vector3d(0.05, 0.05, 2.25)), 0.25, 1e-12);
  EXPECT_NEAR(world.clearance(Vector3d(0.4, 0.05, 2.4)), 0.5, 1e-12);
  EXPECT_LT(world.clearance(Vector3d(0.05, 0.05, 1.0)), 0.0);
  // The ring in the plane x = 5: its centre (the hole), on the tube, off the plane.
  EXPECT_NEAR(world.clearance(Vector3d(5.0, 0.0, 1.25)), 0.6 - 0.05, 1e-9);
  EXPECT_NEAR(world.clearance(Vector3d(5.0, 0.6, 1.25)), -0.05, 1e-9);
  EXPECT_NEAR(world.clearance(Vector3d(5.3, 0.0, 2.25)), 0.3 - 0.05, 1e-9);
  // A vehicle of radius 0.15 collides where the clearance is below it.
  EXPECT_LT(world.clearance(Vector3d(5.1, 0.6, 1.25)), 0.15);
  EXPECT_GT(world.clearance(Vector3d(5.0, 0.3, 1.25)), 0.15);
}

TEST(EgoForestWorld, RaysHitColumnsAndRingsAndPassThroughTheHole) {
  const mmh::sim::EgoForestWorld world(handMadeForest(), {});
  EXPECT_NEAR(world.raycastOne(Vector3d(-2, 0.05, 1), Vector3d(1, 0, 0), 5.0), 2.0, 1e-9);
  // Over the column's top, and down onto it.
  EXPECT_LT(world.raycastOne(Vector3d(-2, 0.05, 2.5), Vector3d(1, 0, 0), 5.0), 0.0);
  EXPECT_NEAR(world.raycastOne(Vector3d(0.05, 0.05, 3), Vector3d(0, 0, -1), 5.0), 1.0, 1e-9);
  // The ring: the tube at y = 0.6, and through the hole at y = 0.
  EXPECT_NEAR(world.raycastOne(Vector3d(2, 0.6, 1.25), Vector3d(1, 0, 0), 5.0), 2.95, 2e-4);
  EXPECT_LT(world.raycastOne(Vector3d(2, 0.0, 1.25), Vector3d(1, 0, 0), 5.0), 0.0);
  EXPECT_NEAR(world.raycastOne(Vector3d(5, 0.0, 1.25), Vector3d(0, 0, 1), 5.0), 0.95, 2e-4);
  EXPECT_EQ(world.raycastOne(Vector3d(0.05, 0.05, 1), Vector3d(1, 0, 0), 5.0), 0.0);
}

TEST(EgoForestWorld, RayHitsLieOnTheSurfaceAndMissesSeeNothing) {
  // Every hit is on an obstacle surface (clearance ~0) and nothing is nearer along the ray.
  const mmh::sim::EgoForestWorld world = mmh::sim::EgoForestWorld::generate(protocolSpec(0.3, 2));
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int hits = 0, rays = 0;
  for (int pose = 0; pose < 12; ++pose) {
    const Vector3d origin(20 * u(rng), 20 * u(rng), 1.2);
    if (world.clearance(origin) < 0.2) continue;
    std::vector<Vector3d> dirs;
    for (int i = 0; i < 100; ++i)
      dirs.push_back(Vector3d(u(rng), u(rng), 0.6 * u(rng)).normalized());
    std::vector<double> ranges;
    world.raycast(origin, dirs, 4.5, &ranges);
    for (size_t i = 0; i < dirs.size(); ++i) {
      ++rays;
      const double end = ranges[i] >= 0.0 ? ranges[i] : 4.5;
      if (ranges[i] >= 0.0) {
        ++hits;
        EXPECT_NEAR(world.clearance(origin + ranges[i] * dirs[i]), 0.0, 2e-4);
      }
      for (double t = 0.0; t < end - 0.02; t += 0.01)
        ASSERT_GT(world.clearance(origin + t * dirs[i]), -1e-9) << "ray passed through an obstacle";
    }
  }
  EXPECT_GT(hits, rays / 10);
}

TEST(EgoForestWorld, TimeBoundPathIsAtLeastTheStraightLine) {
  EgoForestSpec spec = protocolSpec(0.2, 4);
  mmh::sim::EgoForestBoundOptions bound;
  bound.min_m = Vector3d(-30, -30, 0.3);
  bound.max_m = Vector3d(30, 30, 2.7);
  const mmh::sim::EgoForestWorld world = mmh::sim::EgoForestWorld::generate(spec, bound);
  const double straight = (spec.goal - spec.start).norm();
  const double length = world.shortestPathLength(spec.start, spec.goal, 0.15);
  EXPECT_GE(length, straight - 1e-6);
  EXPECT_LT(length, 1.2 * straight);
  // Empty: the straight line (up to the grid's shortening).
  const mmh::sim::EgoForestWorld empty(EgoForest{}, bound);
  EXPECT_NEAR(empty.shortestPathLength(spec.start, spec.goal, 0.15), straight, 0.05);
}

TEST(EgoForestWorld, SimulatorFliesItAndItsSensorSeesIt) {
  mmh::sim::SimOptions options;
  options.world = "ego-forest";
  options.density_per_m2 = 0.3;
  options.seed = 6;
  mmh::sim::SimParams params;
  mmh::sim::Simulator sim(params, options);
  EXPECT_NE(sim.world().describe().find("ego-forest"), std::string::npos);
  EXPECT_GT(sim.metrics().time_bound_s, 14.8 - 1e-6);
  mmh::sim::Sensor sensor(mmh::sim::SensorKind::kLidar, params, 1);
  mmh::sim::Scan scan;
  const Vector3d at = options.start;  // kept 2 m clear; the LiDAR reaches 5 m
  sensor.scan(sim.world(), at, Eigen::Quaterniond::Identity(), &scan);
  ASSERT_GT(scan.num_returns, 100);
  for (int i = 0; i < scan.num_returns; ++i) {
    const Vector3d p(scan.xyz[3 * i], scan.xyz[3 * i + 1], scan.xyz[3 * i + 2]);
    EXPECT_LT(std::abs(sim.world().clearance(p)), 1e-3);
  }
}
