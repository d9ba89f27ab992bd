// PCD worlds: loading, ray casting against the voxelised surface, clearance and the bound.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "mmh/sim/pointcloud_world.hpp"
#include "mmh/sim/simulator.hpp"
#include "pcd_writer.hpp"

using Eigen::Vector3d;

namespace {

std::string tempPath(const std::string& name) {
  return ::testing::TempDir() + "/" + name;
}

}  // namespace

TEST(PointCloudWorld, LoadsAPcdFileAndIsHitByRays) {
  const std::string path = tempPath("wall.pcd");
  mmh::test::writePcd(path, mmh::test::wallPoints(2.0, 1.0, 3.0, 0.02));
  mmh::sim::PointCloudWorldOptions options;
  auto world = mmh::sim::PointCloudWorld::loadPcd(path, options);
  EXPECT_EQ(world->numPoints(), 101u * 151u);
  EXPECT_GT(world->numVoxels(), 0u);
  // Straight at the wall: hit within one voxel of x = 2.
  const double r = world->raycastOne(Vector3d(0, 0, 1.2), Vector3d(1, 0, 0), 5.0);
  EXPECT_NEAR(r, 2.0, options.voxel_m);
  EXPECT_LE(r, 2.0 + 1e-9);
  // Oblique hit, a miss beside the wall, away from it, and beyond the range.
  const Vector3d d = Vector3d(1, 0.3, 0.1).normalized();
  EXPECT_NEAR(world->raycastOne(Vector3d(0, 0, 1.2), d, 5.0), 2.0 / d.x(), 0.1);
  EXPECT_LT(world->raycastOne(Vector3d(0, 0, 1.2), Vector3d(1, 1, 0).normalized(), 5.0), 0.0);
  EXPECT_LT(world->raycastOne(Vector3d(0, 0, 1.2), Vector3d(-1, 0, 0), 5.0), 0.0);
  EXPECT_LT(world->raycastOne(Vector3d(0, 0, 1.2), Vector3d(1, 0, 0), 1.5), 0.0);
  // Negative coordinates (voxel indices below zero) work the same way.
  EXPECT_NEAR(world->raycastOne(Vector3d(4, -0.5, 0.7), Vector3d(-1, 0, 0), 5.0), 2.0, 0.06);
  // Clearance to the nearest surface voxel centre.
  EXPECT_NEAR(world->clearance(Vector3d(0, 0, 1.2)), 2.0, 0.05);
  EXPECT_LT(world->clearance(Vector3d(1.95, 0, 1.2)), 0.15);
  std::remove(path.c_str());
}

TEST(PointCloudWorld, BadFilesAreReportedNotCrashed) {
  mmh::sim::PointCloudWorldOptions options;
  EXPECT_THROW(mmh::sim::PointCloudWorld::loadPcd(tempPath("missing.pcd"), options),
               std::runtime_error);
  const std::string path = tempPath("nan.pcd");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  mmh::test::writePcd(path, {Eigen::Vector3f(nan, nan, nan)});
  EXPECT_THROW(mmh::sim::PointCloudWorld::loadPcd(path, options), std::runtime_error);
  std::remove(path.c_str());
}

TEST(PointCloudWorld, ShortestPathGoesAroundTheWall) {
  mmh::sim::PointCloudWorldOptions options;
  options.bound_min_m = Vector3d(-30, -30, 0.3);
  options.bound_max_m = Vector3d(30, 30, 2.7);
  const mmh::sim::PointCloudWorld world(mmh::test::wallPoints(0.0, 1.0, 3.0, 0.02), options);
  const double length = world.shortestPathLength(Vector3d(-2, 0, 1.2), Vector3d(2, 0, 1.2), 0.15);
  // Round the wall's end at y = +-1, kept 0.15 m away: two legs of hypot(2, 1.15).
  const double expected = 2.0 * std::hypot(2.0, 1.15);
  EXPECT_GT(length, expected - 0.1);
  EXPECT_LT(length, expected + 0.25);
  // Without obstacles in the way: the straight line (up to the grid).
  EXPECT_NEAR(world.shortestPathLength(Vector3d(-2, 3, 1.2), Vector3d(2, 3, 1.2), 0.15), 4.0, 0.1);
}

TEST(PointCloudWorld, SimulatorFliesInAPcdWorld) {
  const std::string path = tempPath("wall_sim.pcd");
  // The wall, and two points on the ground that make the world span the start and the goal
  // (outside its bounds they would be refused).
  auto points = mmh::test::wallPoints(3.0, 2.0, 3.0, 0.02);
  points.emplace_back(-1.0f, 0.0f, 0.0f);
  points.emplace_back(7.0f, 0.0f, 0.0f);
  mmh::test::writePcd(path, points);
  mmh::sim::SimOptions options;
  options.world = path;
  options.start = Vector3d(0, 0, 1.2);
  options.goal = Vector3d(6, 0, 1.2);
  mmh::sim::Simulator sim(mmh::sim::SimParams{}, options);
  EXPECT_GT(sim.metrics().shortest_path_m, 6.0);
  bool scanned = false;
  for (int i = 0; i < 10 && !scanned; ++i) {
    if (sim.step().scan) {
      scanned = true;
      EXPECT_GT(sim.lastScan().num_returns, 1000);  // the wall fills the view 3 m ahead
    }
  }
  EXPECT_TRUE(scanned);
  std::remove(path.c_str());
}
