// The occupancy map against ground truth and against OctoMap's own insertion.
#include <gtest/gtest.h>

#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>

#include "mmh/mapping/occupancy_map.hpp"
#include "scan_helpers.hpp"

using Eigen::Vector3d;
using mmh::Occupancy;

namespace {

mmh::mapping::FilteredScan filtered(const mmh::sim::Scan& scan,
                                    const mmh::mapping::MappingParams& params) {
  mmh::mapping::FilteredScan out;
  mmh::mapping::FilterStats stats;
  EXPECT_EQ(mmh::mapping::filterScan(mmh::test::inputOf(scan), params, &out, &stats, nullptr),
            mmh::mapping::ScanError::kNone);
  return out;
}

}  // namespace

TEST(OccupancyMap, KnownSceneMatchesGroundTruthWithinOneVoxel) {
  const mmh::sim::ForestWorld world = mmh::test::smallForest();
  mmh::mapping::MappingParams params;
  mmh::mapping::OccupancyMap map(params);
  const Vector3d origin(0, 0, 1.2);
  map.followVehicle(origin);
  // Hover and turn round: eight depth frames, twice each.
  std::vector<mmh::sim::Scan> scans;
  for (int k = 0; k < 16; ++k) scans.push_back(mmh::test::scanOf(world, origin, 45.0 * (k % 8)));
  for (const auto& scan : scans) map.insert(filtered(scan, params));
  const mmh::VoxelGrid w = map.window();
  const double res = params.resolution_m;
  int64_t occupied = 0, free = 0;
  for (int64_t i = 0; i < w.numCells(); ++i) {
    const Occupancy s = w.atLinear(i);
    if (s == Occupancy::kUnknown) continue;
    const Vector3d c = w.centerOfLocal(w.localFromLinear(i));
    const double d = world.clearance(c);
    if (s == Occupancy::kOccupied) {
      ++occupied;
      // An occupied voxel holds a surface point: its centre is within half a diagonal.
      EXPECT_LE(std::abs(d), res * std::sqrt(3.0) / 2 + 1e-6) << c.transpose();
    } else {
      ++free;
      // A free voxel may graze a surface but never lies inside an obstacle.
      EXPECT_GE(d, -res * std::sqrt(3.0) / 2) << c.transpose();
    }
  }
  EXPECT_GT(occupied, 1000);
  EXPECT_GT(free, 50000);
  // Every return's voxel is occupied (or, rarely, a grazed voxel that rays crossed more often).
  int returns = 0, marked = 0;
  for (const auto& scan : scans) {
    for (int i = 0; i < scan.num_returns; ++i) {
      const Vector3d p(scan.xyz[3 * i], scan.xyz[3 * i + 1], scan.xyz[3 * i + 2]);
      ++returns;
      marked += w.atPoint(p) == Occupancy::kOccupied;
    }
  }
  EXPECT_GT(marked, 0.97 * returns);
  // Free space is cleared along rays: points between the sensor and the first pillar.
  for (double x = 0.2; x < 1.5; x += 0.1)
    EXPECT_EQ(w.atPoint(Vector3d(x, 0.0, 1.2)), Occupancy::kFree);
  // Open directions are free out to the range, unknown beyond.
  EXPECT_EQ(w.atPoint(Vector3d(-4.2, -1.0, 1.2)), Occupancy::kFree);
  EXPECT_EQ(w.atPoint(Vector3d(-5.5, -1.0, 1.2)), Occupancy::kUnknown);
  // The pillar hidden behind the first one is not mapped, nor is the inside of a pillar.
  EXPECT_EQ(w.atPoint(Vector3d(3.6 - 0.25 + 0.05, 0.0, 1.2)), Occupancy::kUnknown);
  EXPECT_EQ(w.atPoint(Vector3d(2.0, 0.0, 1.2)), Occupancy::kUnknown);
}

TEST(OccupancyMap, SameVoxelsAndLogOddsAsOctoMapInsertPointCloud) {
  const mmh::sim::ForestWorld world = mmh::test::smallForest();
  mmh::mapping::MappingParams params;
  const Vector3d origin(0.03, 0.07, 1.21);
  const auto scan = filtered(mmh::test::scanOf(world, origin, 20.0), params);
  mmh::mapping::OccupancyMap map(params);
  map.followVehicle(origin);
  map.insert(scan);
  // The same rays through OctoMap: returns as end points; free rays placed beyond the range and
  // truncated by maxrange, which OctoMap inserts as free without an obstacle at the end.
  octomap::OcTree ref(params.resolution_m);
  octomap::Pointcloud cloud;
  for (const auto& p : scan.returns) cloud.push_back(p.x(), p.y(), p.z());
  const Eigen::Vector3f o = origin.cast<float>();
  for (const auto& p : scan.free_ends) {
    const Eigen::Vector3f far = o + (p - o) * 1.5f;
    cloud.push_back(far.x(), far.y(), far.z());
  }
  map.flush();
  ref.insertPointCloud(cloud, octomap::point3d(o.x(), o.y(), o.z()), scan.range_m,
                       /*lazy_eval=*/true);  // no pruning: one leaf per voxel, as ours
  // Only the window is mapped (rays going 30 deg down leave its bottom at -0.8 m).
  const mmh::VoxelGrid w = map.window();
  int64_t leaves = 0, same = 0;
  for (auto it = ref.begin_leafs(), end = ref.end_leafs(); it != end; ++it) {
    const Vector3d c(it.getX(), it.getY(), it.getZ());
    if (!w.containsPoint(c)) continue;
    ++leaves;
    const Occupancy expected = ref.isNodeOccupied(*it) ? Occupancy::kOccupied : Occupancy::kFree;
    const auto* node = map.octree().search(it.getKey());
    if (map.query(c) == expected && node && std::abs(node->getLogOdds() - it->getLogOdds()) < 1e-6)
      ++same;
  }
  EXPECT_GT(leaves, 10000);
  // Ray traversals differ only where a ray grazes a voxel corner (floating point).
  EXPECT_GT(same, 0.995 * leaves);
  EXPECT_NEAR(static_cast<double>(map.octreeLeaves()), static_cast<double>(leaves), 0.005 * leaves);
}

TEST(OccupancyMap, ARayGrazingASurfaceDoesNotClearTheCellsBesideWhatTheScanHit) {
  // A trunk's side seen at a glancing angle: the cell (2, 0, 12) was mapped occupied; in the
  // next scans a ray ends on the surface in the cell beside it, (2, 1, 12), and another ray
  // passes through (2, 0, 12) to a tree farther on. That ray may have passed the surface by a
  // hair: the cell stays occupied. The lone hit of the first scan, crossed the same way with no
  // hit beside it, is cleared.
  mmh::mapping::MappingParams params;
  mmh::mapping::OccupancyMap map(params);
  const Vector3d origin(0.05, 0.05, 1.25);
  map.followVehicle(origin);
  const Vector3d hit_cell(0.25, 0.05, 1.25);  // centre of the cell (2, 0, 12)
  mmh::mapping::FilteredScan first;
  first.origin = origin;
  first.range_m = 5.0;
  first.returns = {hit_cell.cast<float>(), Eigen::Vector3f(0.25f, -1.05f, 1.25f)};
  map.insert(first);
  ASSERT_EQ(map.query(hit_cell), Occupancy::kOccupied);
  ASSERT_EQ(map.query(Vector3d(0.25, -1.05, 1.25)), Occupancy::kOccupied);
  // Cells beside a hit that are not mapped occupied are cleared as usual: the one in front of it.
  EXPECT_EQ(map.query(Vector3d(0.15, 0.05, 1.25)), Occupancy::kFree);
  mmh::mapping::FilteredScan grazing = first;
  grazing.returns = {Eigen::Vector3f(0.25f, 0.15f, 1.25f),    // beside the first hit
                     Eigen::Vector3f(3.05f, 0.05f, 1.25f),    // through it, to a farther tree
                     Eigen::Vector3f(1.05f, -5.45f, 1.25f)};  // through the lone hit
  for (int k = 0; k < 5; ++k) map.insert(grazing);
  EXPECT_EQ(map.query(hit_cell), Occupancy::kOccupied);
  EXPECT_EQ(map.query(Vector3d(0.25, -1.05, 1.25)), Occupancy::kFree);
  // Cells between the sensor and the surface are cleared as before.
  EXPECT_EQ(map.query(Vector3d(1.55, 0.05, 1.25)), Occupancy::kFree);
}

TEST(OccupancyMap, WindowFollowsTheVehicleAndRemembersWhatItLeft) {
  const mmh::sim::ForestWorld world = mmh::test::smallForest();
  mmh::mapping::MappingParams params;
  mmh::mapping::OccupancyMap map(params);
  const Vector3d origin(0, 0, 1.2);
  EXPECT_TRUE(map.followVehicle(origin));
  for (int k = 0; k < 8; ++k)
    map.insert(filtered(mmh::test::scanOf(world, origin, 45.0 * k), params));
  const mmh::VoxelGrid before = map.window();
  map.takeChanges();
  // Within the recentring distance the window stays; beyond it moves.
  EXPECT_FALSE(map.followVehicle(origin + Vector3d(0.9, 0.0, 0.0)));
  EXPECT_TRUE(map.followVehicle(origin + Vector3d(1.1, 0.5, 0.2)));
  EXPECT_NE(map.windowOrigin(), before.originIndex());
  // Far away (the window leaves the mapped area entirely), prune, and back.
  EXPECT_TRUE(map.followVehicle(origin + Vector3d(60.0, 0.0, 0.0)));
  EXPECT_EQ(std::count(map.windowStates().begin(), map.windowStates().end(), 2), 0);
  map.flush();
  const size_t leaves_before_prune = map.octreeLeaves();
  map.pruneOutsideWindow();
  EXPECT_LT(map.octreeLeaves(), leaves_before_prune);
  EXPECT_TRUE(map.followVehicle(origin));
  ASSERT_EQ(map.windowOrigin(), before.originIndex());
  EXPECT_EQ(map.windowStates(), before.rawCells());
  // The tree answers the same as the window everywhere in it.
  const mmh::VoxelGrid w = map.window();
  for (int64_t i = 0; i < w.numCells(); i += 7) {
    ASSERT_EQ(map.query(w.centerOfLocal(w.localFromLinear(i))), w.atLinear(i));
  }
  // Inserting again after the round trip (cells under pruned nodes) keeps tree and window equal.
  map.insert(filtered(mmh::test::scanOf(world, origin + Vector3d(0.3, 0.2, 0), 10.0), params));
  const mmh::VoxelGrid after = map.window();
  for (int64_t i = 0; i < after.numCells(); i += 7) {
    ASSERT_EQ(map.query(after.centerOfLocal(after.localFromLinear(i))), after.atLinear(i));
  }
}
