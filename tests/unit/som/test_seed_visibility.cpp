// Seed visibility against a hand-made grid: one occupied cell, inflated, so that the blocked
// cells and their faces are known exactly.
#include <gtest/gtest.h>

#include "mmh/som/seed_visibility.hpp"
#include "som_test_worlds.hpp"

using Eigen::Vector3d;

namespace {

// One occupied cell centred at (5.05, 0.05, 1.25); inflated by 0.1 m the blocked cells are it
// and its six face neighbours, so the cells at y in [0.1, 0.2] are blocked only above it.
som_test::World oneCell() {
  return som_test::makeWorld(
      [](const Vector3d& p) { return (p - Vector3d(5.05, 0.05, 1.25)).norm() < 0.01; }, 0.1);
}

}  // namespace

TEST(SeedVisibility, ASegmentPastABlockedCellIsVisibleOnlyWithoutAClearanceWhenItGrazesIt) {
  const som_test::World w = oneCell();
  const mmh::VoxelGrid& g = *w.grid;
  ASSERT_TRUE(g.isBlockedPoint(Vector3d(5.05, 0.15, 1.25)));   // the neighbour in +y
  ASSERT_FALSE(g.isBlockedPoint(Vector3d(5.15, 0.15, 1.25)));  // its diagonal neighbour
  // Along x, 1 mm above the blocked neighbour's +y face (at y = 0.2).
  const Vector3d a(4.0, 0.201, 1.25), b(6.0, 0.201, 1.25);
  EXPECT_TRUE(mmh::som::segmentVisible(g, a, b, {}));
  EXPECT_FALSE(mmh::som::segmentVisible(g, a, b, {}, 0.042));
  // 5 cm above it, the clearance is kept.
  const Vector3d up(0.0, 0.05, 0.0);
  EXPECT_TRUE(mmh::som::segmentVisible(g, a + up, b + up, {}, 0.042));
  // Through the blocked cells, nothing is visible.
  EXPECT_FALSE(mmh::som::segmentVisible(g, Vector3d(4.0, 0.1, 1.25), Vector3d(6.0, 0.1, 1.25), {}));
}

TEST(SeedVisibility, CellsTheEscapeZoneFreesCountAsFreeWithTheClearanceToo) {
  const som_test::World w = oneCell();
  const mmh::VoxelGrid& g = *w.grid;
  const Vector3d a(4.0, 0.201, 1.25), b(6.0, 0.201, 1.25);
  mmh::som::EscapeZone escape;
  escape.center = Vector3d(5.05, 0.15, 1.25);  // in the blocked neighbour, which it frees
  escape.radius = 0.05;
  EXPECT_TRUE(mmh::som::seedBlockedAt(g, Vector3d(5.05, 0.15, 1.25), {}));
  EXPECT_FALSE(mmh::som::seedBlockedAt(g, Vector3d(5.05, 0.15, 1.25), escape));
  EXPECT_TRUE(mmh::som::seedBlockedAt(g, Vector3d(5.05, 0.05, 1.25), escape));  // occupied
  EXPECT_TRUE(mmh::som::segmentVisible(g, a, b, escape, 0.042));
}

TEST(SeedVisibility, ATriangleIsFreeWhenNoneOfItsFanSegmentsCrossesABlockedCell) {
  const som_test::World w = oneCell();
  const mmh::VoxelGrid& g = *w.grid;
  const Vector3d a(4.0, 0.5, 1.25), b(6.0, 0.5, 1.25);
  EXPECT_TRUE(mmh::som::triangleVisible(g, a, b, Vector3d(5.0, 1.5, 1.25), {}));
  // Its apex beyond the cell: the fan crosses it.
  EXPECT_FALSE(mmh::som::triangleVisible(g, a, b, Vector3d(5.05, -0.5, 1.25), {}));
  // Apex 1 mm above the blocked neighbour: free, but not with a clearance.
  const Vector3d apex(5.05, 0.201, 1.25);
  EXPECT_TRUE(mmh::som::triangleVisible(g, a, b, apex, {}));
  EXPECT_FALSE(mmh::som::triangleVisible(g, a, b, apex, {}, 0.042));
}
