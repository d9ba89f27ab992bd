// World files: PCD bounds and the start/goal check against them, --fit-geofence, and a generated
// forest written as a PCD (--export-world) that the point-cloud world reads back as the same
// obstacles.
#include <gtest/gtest.h>

#include <cstdio>
#include <stdexcept>

#include "mmh/common/forest.hpp"
#include "mmh/sim/forest_world.hpp"
#include "mmh/sim/pointcloud_world.hpp"
#include "mmh/sim/simulator.hpp"
#include "mmh/sim/world_file.hpp"
#include "pcd_writer.hpp"

using Eigen::Vector3d;
using mmh::sim::WorldBounds;

namespace {

std::string tempPath(const std::string& name) {
  return ::testing::TempDir() + "/" + name;
}

}  // namespace

TEST(WorldFile, BoundsViolationNamesTheCoordinatesAndTheBounds) {
  const WorldBounds b{Vector3d(-10, -5, 0), Vector3d(10, 5, 3)};
  EXPECT_EQ(mmh::sim::worldBoundsViolation(b, Vector3d(0, 0, 1), "the goal", "w.pcd"), "");
  // z is the geofence's business, not the world's.
  EXPECT_EQ(mmh::sim::worldBoundsViolation(b, Vector3d(0, 0, 9), "the goal", "w.pcd"), "");
  const std::string why =
      mmh::sim::worldBoundsViolation(b, Vector3d(15, -6, 1.2), "the goal", "w.pcd");
  EXPECT_NE(why.find("the goal [15, -6, 1.2] lies outside the world's bounds (x = 15 > 10, "
                     "y = -6 < -5): w.pcd spans x [-10, 10], y [-5, 5]"),
            std::string::npos)
      << why;
  // The one check: the geofence first, then the world.
  const mmh::Geofence fence;  // +-30 m, z 0.3 .. 2.7
  EXPECT_EQ(mmh::sim::startGoalViolation(Vector3d(-9, 0, 1), Vector3d(9, 0, 1), fence, &b, "w"),
            "");
  EXPECT_NE(mmh::sim::startGoalViolation(Vector3d(-11, 0, 1), Vector3d(9, 0, 1), fence, &b, "w")
                .find("the start [-11, 0, 1] lies outside the world's bounds"),
            std::string::npos);
  EXPECT_NE(mmh::sim::startGoalViolation(Vector3d(-9, 0, 1), Vector3d(40, 0, 1), fence, &b, "w")
                .find("the goal [40, 0, 1] lies outside the geofence"),
            std::string::npos);
  EXPECT_EQ(
      mmh::sim::startGoalViolation(Vector3d(-11, 0, 1), Vector3d(9, 0, 1), fence, nullptr, "w"),
      "");
}

TEST(WorldFile, FitGeofenceWidensXYAndKeepsZ) {
  const WorldBounds b{Vector3d(-10.123, -5.0, -1.0), Vector3d(10.001, 5.0, 7.0)};
  mmh::Geofence configured;
  configured.min_m = Vector3d(-30, -30, 0.3);
  configured.max_m = Vector3d(30, 30, 2.7);
  const mmh::Geofence f = mmh::sim::fitGeofence(b, configured, 1.0);
  EXPECT_NEAR(f.min_m.x(), -11.13, 1e-9);  // rounded outwards to the centimetre
  EXPECT_NEAR(f.max_m.x(), 11.01, 1e-9);
  EXPECT_NEAR(f.min_m.y(), -6.0, 1e-9);
  EXPECT_NEAR(f.max_m.y(), 6.0, 1e-9);
  EXPECT_EQ(f.min_m.z(), 0.3);
  EXPECT_EQ(f.max_m.z(), 2.7);
  const auto sets = mmh::sim::geofenceAssignments(f);
  ASSERT_EQ(sets.size(), 2u);
  EXPECT_EQ(sets[0], "geofence.min_m=[-11.13, -6, 0.3]");
  EXPECT_EQ(sets[1], "geofence.max_m=[11.01, 6, 2.7]");
}

TEST(WorldFile, ConfigWithGeofenceReplacesOnlyTheFence) {
  const mmh::Config config =
      mmh::Config::loadFile(std::string(MMH_SOURCE_DIR) + "/deploy/config/default.yaml");
  mmh::Geofence f;
  f.min_m = Vector3d(-5, -4, 0.5);
  f.max_m = Vector3d(6, 7, 2.5);
  const mmh::Config fitted = mmh::sim::configWithGeofence(config, f);
  EXPECT_EQ(fitted.getVector3("geofence.min_m"), f.min_m);
  EXPECT_EQ(fitted.getVector3("geofence.max_m"), f.max_m);
  EXPECT_EQ(fitted.getDouble("vehicle.max_vel_mps"), config.getDouble("vehicle.max_vel_mps"));
}

TEST(WorldFile, ExportedForestIsTheSameWorldAsAPointCloud) {
  mmh::sim::SimOptions o;
  o.size_m = Vector3d(12, 12, 3);
  o.density_per_m2 = 0.1;
  o.seed = 5;
  o.start = Vector3d(-5, 0, 1.2);
  o.goal = Vector3d(5, 0, 1.2);
  const auto points = mmh::sim::generatedWorldPoints(o, 0.05);
  ASSERT_FALSE(points.empty());
  const std::string path = tempPath("forest.pcd");
  mmh::sim::writePcd(path, points);
  const WorldBounds b = mmh::sim::readPcdBounds(path);
  mmh::sim::PointCloudWorldOptions po;
  const auto cloud = mmh::sim::PointCloudWorld::loadPcd(path, po);
  EXPECT_EQ(cloud->numPoints(), points.size());
  EXPECT_EQ(b.min_m, cloud->minCorner());
  EXPECT_EQ(b.max_m, cloud->maxCorner());
  // Every exported point lies on a cylinder's mantle or top disc (or inside an
  // overlapping one), and every cylinder is covered.
  mmh::ForestSpec spec;
  spec.size_m = o.size_m;
  spec.density_per_m2 = o.density_per_m2;
  spec.seed = static_cast<uint64_t>(o.seed);
  spec.start = o.start;
  spec.goal = o.goal;
  const auto forest = mmh::generateForest(spec);
  for (size_t i = 0; i < points.size(); i += 97) {
    const Vector3d p = points[i].cast<double>();
    const double d = mmh::distanceToForest(forest, p);
    EXPECT_LT(d, 1e-3);
  }
  for (const mmh::Cylinder& c : forest) {
    const Vector3d side(c.center.x() + c.radius + 0.2, c.center.y(), 1.5);
    // 0.2 m off the mantle (or nearer another cylinder): the cloud's clearance (to 5 cm voxel
    // centres) agrees with the forest's.
    const double truth = mmh::distanceToForest(forest, side);
    if (truth > 0.1) {
      EXPECT_NEAR(cloud->clearance(side), truth, 0.06);
    }
  }
  std::remove(path.c_str());
  o.world = "x.pcd";
  EXPECT_THROW(mmh::sim::generatedWorldPoints(o), std::runtime_error);
}

TEST(WorldFile, SimulatorRefusesAGoalOutsideThePcdWorld) {
  const std::string path = tempPath("wall2.pcd");
  mmh::test::writePcd(path, mmh::test::wallPoints(0.0, 3.0, 3.0, 0.05));
  mmh::sim::SimParams params;
  mmh::sim::SimOptions o;
  o.world = path;
  o.start = Vector3d(-2, 0, 1.2);  // x: the wall is one plane at x = 0, so extend it below
  o.goal = Vector3d(0, 2, 1.2);
  try {
    mmh::sim::Simulator sim(params, o);
    FAIL() << "the start lies outside the world";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("the start [-2, 0, 1.2] lies outside the world's bounds "
                                         "(x = -2 < 0)"),
              std::string::npos)
        << e.what();
  }
  std::remove(path.c_str());
}
