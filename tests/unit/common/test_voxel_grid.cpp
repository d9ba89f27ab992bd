#include <gtest/gtest.h>

#include <vector>

#include "mmh/common/collision_check.hpp"
#include "mmh/common/voxel_grid.hpp"

using Eigen::Vector3d;
using Eigen::Vector3i;
using mmh::Occupancy;
using mmh::VoxelGrid;

TEST(VoxelGrid, WorldIndexConversions) {
  VoxelGrid g(0.1, Vector3i(-50, -50, 0), Vector3i(100, 100, 30));
  EXPECT_EQ(g.globalIndexOf(Vector3d(0.05, -0.05, 1.23)), Vector3i(0, -1, 12));
  EXPECT_EQ(g.localIndexOf(Vector3d(0.05, -0.05, 1.23)), Vector3i(50, 49, 12));
  EXPECT_TRUE(g.centerOfLocal(Vector3i(50, 49, 12)).isApprox(Vector3d(0.05, -0.05, 1.25)));
  EXPECT_TRUE(g.containsPoint(Vector3d(-4.99, 4.99, 0.01)));
  EXPECT_FALSE(g.containsPoint(Vector3d(5.01, 0, 1)));
  EXPECT_FALSE(g.containsPoint(Vector3d(0, 0, -0.01)));
  for (int64_t i : {int64_t{0}, int64_t{12345}, g.numCells() - 1}) {
    EXPECT_EQ(g.linearIndex(g.localFromLinear(i)), i);
  }
  EXPECT_TRUE(g.minCorner().isApprox(Vector3d(-5, -5, 0)));
  EXPECT_TRUE(g.maxCorner().isApprox(Vector3d(5, 5, 3)));
}

TEST(VoxelGrid, StatesAndOutsideIsUnknown) {
  VoxelGrid g(0.2, Vector3i(0, 0, 0), Vector3i(10, 10, 10));
  EXPECT_EQ(g.at(Vector3i(1, 2, 3)), Occupancy::kUnknown);
  g.set(Vector3i(1, 2, 3), Occupancy::kOccupied);
  g.set(Vector3i(1, 2, 4), Occupancy::kFree);
  EXPECT_EQ(g.at(Vector3i(1, 2, 3)), Occupancy::kOccupied);
  EXPECT_EQ(g.atPoint(Vector3d(0.3, 0.5, 0.9)), Occupancy::kFree);
  EXPECT_EQ(g.at(Vector3i(-1, 0, 0)), Occupancy::kUnknown);
  EXPECT_EQ(g.numOccupied(), 1);
}

TEST(VoxelGrid, InflationCoversTheRadiusOnlyAndIsIncremental) {
  VoxelGrid g(0.1, Vector3i(0, 0, 0), Vector3i(40, 40, 40));
  g.setInflationRadius(0.3);
  const Vector3i c(20, 20, 20);
  g.set(c, Occupancy::kOccupied);
  EXPECT_TRUE(g.isBlocked(c));
  EXPECT_TRUE(g.isBlocked(c + Vector3i(3, 0, 0)));   // 0.3 m away
  EXPECT_FALSE(g.isBlocked(c + Vector3i(4, 0, 0)));  // 0.4 m away
  EXPECT_TRUE(g.isBlocked(c + Vector3i(2, 2, 0)));   // 0.283 m
  EXPECT_FALSE(g.isBlocked(c + Vector3i(3, 3, 0)));  // 0.424 m
  // Two obstacles overlap; removing one keeps the other's zone.
  g.set(c + Vector3i(2, 0, 0), Occupancy::kOccupied);
  g.set(c, Occupancy::kFree);
  EXPECT_TRUE(g.isBlocked(c + Vector3i(5, 0, 0)));
  EXPECT_TRUE(g.isBlocked(c));
  EXPECT_FALSE(g.isBlocked(c + Vector3i(-2, 0, 0)));
  g.set(c + Vector3i(2, 0, 0), Occupancy::kFree);
  EXPECT_FALSE(g.isBlocked(c + Vector3i(2, 0, 0)));
  // Changing the radius rebuilds.
  g.set(c, Occupancy::kOccupied);
  g.setInflationRadius(0.5);
  EXPECT_TRUE(g.isBlocked(c + Vector3i(5, 0, 0)));
}

TEST(VoxelGrid, ShiftKeepsOverlapAndInflation) {
  VoxelGrid g(0.1, Vector3i(0, 0, 0), Vector3i(20, 20, 10));
  g.setInflationRadius(0.2);
  g.set(Vector3i(15, 15, 5), Occupancy::kOccupied);  // global (15, 15, 5)
  g.set(Vector3i(1, 1, 5), Occupancy::kOccupied);    // leaves the window after the shift
  g.set(Vector3i(12, 12, 5), Occupancy::kFree);
  g.shiftTo(Vector3i(5, 5, 0));
  EXPECT_EQ(g.at(Vector3i(10, 10, 5)), Occupancy::kOccupied);
  EXPECT_EQ(g.at(Vector3i(7, 7, 5)), Occupancy::kFree);
  EXPECT_EQ(g.at(Vector3i(17, 17, 5)), Occupancy::kUnknown);  // entered
  EXPECT_EQ(g.numOccupied(), 1);
  EXPECT_TRUE(g.isBlocked(Vector3i(12, 10, 5)));
  EXPECT_FALSE(g.isBlocked(Vector3i(0, 0, 5)));  // the obstacle that left took its zone along
  // Same as a grid built directly at the new origin.
  VoxelGrid h(0.1, Vector3i(5, 5, 0), Vector3i(20, 20, 10));
  h.setInflationRadius(0.2);
  h.set(Vector3i(10, 10, 5), Occupancy::kOccupied);
  for (int64_t i = 0; i < g.numCells(); ++i) {
    ASSERT_EQ(g.isBlockedLinear(i), h.isBlockedLinear(i)) << i;
  }
}

TEST(VoxelGrid, ShiftMatchesAFreshGridInEveryDirection) {
  // Obstacles everywhere, including next to the faces, and shifts along every axis and sign:
  // states and inflation must equal a grid built directly at the new origin.
  const Vector3i size(23, 17, 9);
  for (const Vector3i& shift : {Vector3i(3, 0, 0), Vector3i(-4, 2, 0), Vector3i(1, -3, 2),
                                Vector3i(-2, -2, -1), Vector3i(0, 0, 5), Vector3i(30, 0, 0)}) {
    VoxelGrid g(0.1, Vector3i(5, -7, 2), size);
    g.setInflationRadius(0.25);
    for (int64_t i = 0; i < g.numCells(); i += 7) g.setLinear(i, mmh::Occupancy::kOccupied);
    for (int64_t i = 3; i < g.numCells(); i += 11) g.setLinear(i, mmh::Occupancy::kFree);
    VoxelGrid moved = g;
    moved.shiftTo(g.originIndex() + shift);
    VoxelGrid fresh(0.1, g.originIndex() + shift, size);
    fresh.setInflationRadius(0.25);
    for (int64_t i = 0; i < fresh.numCells(); ++i) {
      const Vector3i old_local = fresh.localFromLinear(i) + shift;
      if (g.inWindow(old_local)) fresh.setLinear(i, g.at(old_local));
    }
    ASSERT_EQ(moved.rawCells(), fresh.rawCells()) << shift.transpose();
    ASSERT_EQ(moved.numOccupied(), fresh.numOccupied());
    for (int64_t i = 0; i < fresh.numCells(); ++i) {
      ASSERT_EQ(moved.isBlockedLinear(i), fresh.isBlockedLinear(i))
          << "shift " << shift.transpose() << " cell " << fresh.localFromLinear(i).transpose();
    }
  }
}

TEST(CollisionCheck, SegmentsAndTrajectories) {
  VoxelGrid g(0.1, Vector3i(0, 0, 0), Vector3i(50, 50, 20));
  g.setInflationRadius(0.2);
  for (int z = 0; z < 20; ++z) g.set(Vector3i(25, 25, z), Occupancy::kOccupied);  // thin pole
  EXPECT_FALSE(mmh::isSegmentFree(g, Vector3d(1.0, 2.55, 1.0), Vector3d(4.0, 2.55, 1.0)));
  EXPECT_TRUE(mmh::isSegmentFree(g, Vector3d(1.0, 1.5, 1.0), Vector3d(4.0, 1.5, 1.0)));
  // Passes 0.25 m from the pole centre: free of occupied cells, blocked by inflation.
  EXPECT_FALSE(mmh::isSegmentFree(g, Vector3d(1.0, 2.8, 1.0), Vector3d(4.0, 2.8, 1.0)));
  EXPECT_TRUE(mmh::isSegmentFree(g, Vector3d(1.0, 2.8, 1.0), Vector3d(4.0, 2.8, 1.0),
                                 mmh::CollisionLayer::kOccupied));
  mmh::Piece p;
  p.duration = 3.0;
  p.coeffs(0, 0) = 1.0;
  p.coeffs(0, 1) = 1.0;  // x = 1 + t
  p.coeffs(1, 0) = 2.55;
  p.coeffs(2, 0) = 1.0;
  auto hit = mmh::firstCollisionTime(g, mmh::Trajectory({p}), 0.0, 3.0);
  ASSERT_TRUE(hit.has_value());
  // Blocked zone starts at x = 2.5 - 0.2 (cell centres within 0.2 m of the pole's cell).
  EXPECT_NEAR(*hit, 1.3, 0.06);
  EXPECT_FALSE(mmh::firstCollisionTime(g, mmh::Trajectory({p}), 0.0, 1.2).has_value());
}

// At the window's faces and corners, and from points outside it, only occupied cells inside the
// window count: checked against every occupied cell's centre.
TEST(CollisionCheck, OccupiedDistanceAtTheWindowsEdgesCountsTheCellsInside) {
  mmh::VoxelGrid g(0.1, Eigen::Vector3i(-5, 3, 0), Eigen::Vector3i(12, 9, 6));
  for (int64_t i = 0; i < g.numCells(); ++i) g.setLinear(i, mmh::Occupancy::kFree);
  const std::vector<Eigen::Vector3i> occupied = {{0, 0, 0}, {11, 8, 5}, {0, 8, 2}, {6, 4, 3}};
  for (const Eigen::Vector3i& c : occupied) g.set(c, mmh::Occupancy::kOccupied);
  auto brute = [&](const Eigen::Vector3d& p, double limit) {
    double best = limit;
    for (const Eigen::Vector3i& c : occupied)
      best = std::min(best, (g.centerOfLocal(c) - p).norm());
    return best;
  };
  const Eigen::Vector3d lo = g.minCorner(), hi = g.maxCorner();
  int checked = 0;
  for (double x = lo.x() - 0.25; x <= hi.x() + 0.25; x += 0.07)
    for (double y = lo.y() - 0.25; y <= hi.y() + 0.25; y += 0.07)
      for (double z = lo.z() - 0.25; z <= hi.z() + 0.25; z += 0.07) {
        const Eigen::Vector3d p(x, y, z);
        ASSERT_NEAR(mmh::occupiedDistance(g, p, 0.35), brute(p, 0.35), 1e-12) << p.transpose();
        ++checked;
      }
  EXPECT_GT(checked, 1000);
}

TEST(CollisionCheck, OccupiedDistanceAndTheEscapeRule) {
  mmh::VoxelGrid g(0.1, Eigen::Vector3i(0, 0, 0), Eigen::Vector3i(20, 20, 10));
  for (int64_t i = 0; i < g.numCells(); ++i) g.setLinear(i, mmh::Occupancy::kFree);
  g.setInflationRadius(0.3);
  g.set(Eigen::Vector3i(10, 10, 5), mmh::Occupancy::kOccupied);  // centre (1.05, 1.05, 0.55)
  const Eigen::Vector3d centre(1.05, 1.05, 0.55);
  EXPECT_NEAR(mmh::occupiedDistance(g, centre + Eigen::Vector3d(0.2, 0, 0), 0.5), 0.2, 1e-12);
  EXPECT_NEAR(mmh::occupiedDistance(g, centre + Eigen::Vector3d(0.1, 0.1, 0), 0.5), std::sqrt(0.02),
              1e-12);
  EXPECT_DOUBLE_EQ(mmh::occupiedDistance(g, centre + Eigen::Vector3d(0.6, 0, 0), 0.5), 0.5);
  // A start 0.2 m away may move outwards or round at 0.2 m, not inwards; the distance asked for
  // is capped by the floor.
  const Eigen::Vector3d start = centre + Eigen::Vector3d(0.2, 0, 0);
  const double d = mmh::escapeMinDistance(g, start, 0.28);
  EXPECT_NEAR(d, 0.2, 1e-12);
  EXPECT_TRUE(mmh::keepsEscapeDistance(g, centre + Eigen::Vector3d(0.3, 0, 0), d));
  EXPECT_TRUE(mmh::keepsEscapeDistance(g, centre + Eigen::Vector3d(0, 0.2, 0), d));
  EXPECT_FALSE(mmh::keepsEscapeDistance(g, centre + Eigen::Vector3d(0.15, 0, 0), d));
  EXPECT_NEAR(mmh::escapeMinDistance(g, centre + Eigen::Vector3d(0.29, 0, 0), 0.25), 0.25, 1e-12);
}
