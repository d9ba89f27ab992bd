#include <gtest/gtest.h>

#include "mmh/viewer/voxel_layer.hpp"

namespace mmh::viewer {
namespace {

VoxelGrid window(int ox = -10) {
  return VoxelGrid(0.1, Eigen::Vector3i(ox, -10, 0), {20, 20, 10});
}

TEST(VoxelLayer, KeyframeAddsEveryOccupiedCellAsGlobalIndices) {
  VoxelGrid grid = window();
  grid.set({1, 2, 3}, Occupancy::kOccupied);
  grid.set({4, 5, 6}, Occupancy::kOccupied);
  grid.set({7, 7, 7}, Occupancy::kFree);
  VoxelLayer layer;
  VoxelChanges changes;
  ASSERT_TRUE(layer.apply(makeKeyframe(grid, 1), &changes));
  EXPECT_EQ(layer.numOccupied(), 2u);
  EXPECT_EQ(changes.added.size(), 6u);
  EXPECT_TRUE(changes.removed.empty());
  EXPECT_TRUE(layer.isOccupied(-9, -8, 3));
  EXPECT_TRUE(layer.isOccupied(-6, -5, 6));
  EXPECT_DOUBLE_EQ(layer.resolution(), 0.1);
}

TEST(VoxelLayer, DeltaSendsOnlyTheChangedVoxels) {
  VoxelGrid grid = window();
  grid.set({1, 2, 3}, Occupancy::kOccupied);
  VoxelLayer layer;
  VoxelChanges changes;
  ASSERT_TRUE(layer.apply(makeKeyframe(grid, 1), &changes));
  grid.set({1, 2, 3}, Occupancy::kFree);
  grid.set({2, 2, 2}, Occupancy::kOccupied);
  const std::vector<CellChange> cells = {
      {grid.linearIndex({2, 2, 2}), Occupancy::kOccupied},
      {grid.linearIndex({1, 2, 3}), Occupancy::kFree},
  };
  std::vector<CellChange> sorted = cells;
  std::sort(sorted.begin(), sorted.end());
  ASSERT_TRUE(layer.apply(makeDelta(grid, 2, sorted), &changes));
  EXPECT_EQ(changes.added, (std::vector<int32_t>{-8, -8, 2}));
  EXPECT_EQ(changes.removed, (std::vector<int32_t>{-9, -8, 3}));
  EXPECT_EQ(layer.numOccupied(), 1u);
  // The keyframe the mapping service sends after this delta: nothing to draw, nothing refused.
  ASSERT_TRUE(layer.apply(makeKeyframe(grid, 2), &changes));
  EXPECT_TRUE(changes.empty());
  EXPECT_EQ(layer.numOccupied(), 1u);
}

TEST(VoxelLayer, VoxelsThatLeaveTheWindowStayAndAKeyframeClearsOnlyInsideIt) {
  VoxelGrid grid = window();
  grid.set({0, 0, 0}, Occupancy::kOccupied);   // global (-10, -10, 0)
  grid.set({19, 0, 0}, Occupancy::kOccupied);  // global (9, -10, 0)
  VoxelLayer layer;
  VoxelChanges changes;
  ASSERT_TRUE(layer.apply(makeKeyframe(grid, 1), &changes));
  // The window moves 5 cells along x: (-10, -10, 0) leaves it; (9, -10, 0) is now free.
  grid.shiftTo({-5, -10, 0});
  grid.set({14, 0, 0}, Occupancy::kFree);
  ASSERT_TRUE(layer.apply(makeKeyframe(grid, 2), &changes));
  EXPECT_TRUE(layer.isOccupied(-10, -10, 0));
  EXPECT_FALSE(layer.isOccupied(9, -10, 0));
  EXPECT_EQ(changes.removed, (std::vector<int32_t>{9, -10, 0}));
  EXPECT_TRUE(changes.added.empty());
}

TEST(VoxelLayer, AGapIsRefusedAndLeavesTheLayerUnchanged) {
  VoxelGrid grid = window();
  grid.set({1, 1, 1}, Occupancy::kOccupied);
  VoxelLayer layer;
  VoxelChanges changes;
  ASSERT_TRUE(layer.apply(makeKeyframe(grid, 1), &changes));
  grid.set({2, 2, 2}, Occupancy::kOccupied);
  std::string why;
  EXPECT_FALSE(
      layer.apply(makeDelta(grid, 9, {{grid.linearIndex({2, 2, 2}), Occupancy::kOccupied}}, 8),
                  &changes, &why));
  EXPECT_FALSE(why.empty());
  EXPECT_TRUE(changes.empty());
  EXPECT_EQ(layer.numOccupied(), 1u);
}

TEST(VoxelLayer, NegativeAndLargeIndicesSurviveTheKey) {
  VoxelGrid grid(0.1, Eigen::Vector3i(-100000, 100000, -50), {4, 4, 4});
  grid.set({3, 3, 3}, Occupancy::kOccupied);
  VoxelLayer layer;
  VoxelChanges changes;
  ASSERT_TRUE(layer.apply(makeKeyframe(grid, 1), &changes));
  EXPECT_EQ(layer.allOccupied(), (std::vector<int32_t>{-99997, 100003, -47}));
}

}  // namespace
}  // namespace mmh::viewer
