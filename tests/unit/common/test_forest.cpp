#include <gtest/gtest.h>

#include "mmh/common/forest.hpp"

using Eigen::Vector3d;

TEST(Forest, ExactCountClearanceAndDeterminism) {
  mmh::ForestSpec spec;
  spec.density_per_m2 = 0.1;
  spec.seed = 7;
  auto a = mmh::generateForest(spec);
  EXPECT_EQ(a.size(), 250u);  // 0.1 x 50 x 50
  for (const auto& c : a) {
    EXPECT_GE(c.radius, 0.125 - 1e-12);
    EXPECT_LE(c.radius, 0.525 + 1e-12);
    EXPECT_LE(std::abs(c.center.x()), 25.0);
    EXPECT_GE((c.center - spec.start.head<2>()).norm() - c.radius, 2.0);
    EXPECT_GE((c.center - spec.goal.head<2>()).norm() - c.radius, 2.0);
  }
  auto b = mmh::generateForest(spec);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_TRUE(a[17].center.isApprox(b[17].center));
  spec.seed = 8;
  EXPECT_FALSE(mmh::generateForest(spec)[17].center.isApprox(a[17].center));
  spec.density_per_m2 = 0.0;
  EXPECT_TRUE(mmh::generateForest(spec).empty());
  spec.density_per_m2 = -1.0;
  EXPECT_THROW(mmh::generateForest(spec), std::invalid_argument);
}

TEST(Forest, RasterizeMarksCylinderCells) {
  std::vector<mmh::Cylinder> forest{{Eigen::Vector2d(1.0, 1.0), 0.3, 0.0, 3.0}};
  mmh::VoxelGrid g(0.1, Eigen::Vector3i(0, 0, 0), Eigen::Vector3i(20, 20, 30));
  mmh::rasterizeForest(forest, g);
  EXPECT_EQ(g.atPoint(Vector3d(1.05, 1.05, 1.0)), mmh::Occupancy::kOccupied);
  EXPECT_EQ(g.atPoint(Vector3d(1.35, 1.05, 1.0)), mmh::Occupancy::kFree);
  EXPECT_EQ(g.atPoint(Vector3d(0.25, 1.05, 2.95)), mmh::Occupancy::kFree);
  EXPECT_NEAR(mmh::distanceToForest(forest, Vector3d(2.0, 1.0, 1.0)), 0.7, 1e-12);
  EXPECT_LT(mmh::distanceToForest(forest, Vector3d(1.0, 1.1, 1.0)), 0.0);
}
