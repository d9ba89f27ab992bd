// A world given as surface points (a PCD file read with PCL): the points are voxelised into a
// sparse two-level hash (blocks of 8^3 voxels with a bit per voxel) so that rays skip empty
// blocks; clearance and collisions use a kd-tree (PCL) on the voxel-downsampled points.
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "mmh/sim/world.hpp"

namespace mmh::sim {

struct PointCloudWorldOptions {
  double voxel_m = 0.05;      // ray-casting voxel edge
  double bound_grid_m = 0.1;  // A* grid of the shortest-path bound
  // The bound's path stays in this box (the geofence); the grid is clipped to it and to the
  // points' extent plus a margin.
  Eigen::Vector3d bound_min_m = Eigen::Vector3d(-1e4, -1e4, -1e4);
  Eigen::Vector3d bound_max_m = Eigen::Vector3d(1e4, 1e4, 1e4);
};

class PointCloudWorld : public World {
 public:
  // Non-finite points are dropped. Throws std::invalid_argument if no finite point remains.
  PointCloudWorld(const std::vector<Eigen::Vector3f>& points,
                  const PointCloudWorldOptions& options);
  ~PointCloudWorld() override;
  // Reads a PCD file (x, y, z fields); throws std::runtime_error with the reason on failure.
  static std::unique_ptr<PointCloudWorld> loadPcd(const std::string& path,
                                                  const PointCloudWorldOptions& options);

  size_t numPoints() const { return num_points_; }  // finite points given
  size_t numVoxels() const { return num_voxels_; }  // occupied ray-casting voxels
  const Eigen::Vector3d& minCorner() const { return lo_; }
  const Eigen::Vector3d& maxCorner() const { return hi_; }
  bool voxelOccupied(const Eigen::Vector3i& voxel) const;

  void raycast(const Eigen::Vector3d& origin, const std::vector<Eigen::Vector3d>& dirs,
               double max_range, std::vector<double>* ranges) const override;
  // Distance to the nearest (downsampled) point.
  double clearance(const Eigen::Vector3d& p) const override;
  double shortestPathLength(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            double radius) const override;
  std::string describe() const override;

 private:
  static constexpr int kBlockEdge = 8;
  using BlockBits = std::array<uint64_t, kBlockEdge * kBlockEdge * kBlockEdge / 64>;
  static uint64_t blockKey(const Eigen::Vector3i& block);
  const BlockBits* findBlock(const Eigen::Vector3i& block) const;
  double castOne(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double max_range) const;

  PointCloudWorldOptions options_;
  std::unordered_map<uint64_t, uint32_t> block_index_;
  std::vector<BlockBits> blocks_;
  size_t num_points_ = 0, num_voxels_ = 0;
  Eigen::Vector3d lo_, hi_;
  std::vector<Eigen::Vector3f> surface_;  // voxel-downsampled points, for the kd-tree and A*
  struct KdTree;
  std::unique_ptr<KdTree> kdtree_;
};

}  // namespace mmh::sim
