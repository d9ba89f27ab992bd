#include "mmh/sim/pointcloud_world.hpp"

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "cell_traversal.hpp"
#include "mmh/common/voxel_grid.hpp"
#include "mmh/sim/shortest_path.hpp"
#include "mmh/sim/world_file.hpp"

namespace mmh::sim {

struct PointCloudWorld::KdTree {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud{new pcl::PointCloud<pcl::PointXYZ>};
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
};

namespace {

int floorDiv(int a, int b) {
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

}  // namespace

uint64_t PointCloudWorld::blockKey(const Eigen::Vector3i& block) {
  // 21 bits per axis around an offset: +-1M blocks, i.e. +-400 km at 5 cm voxels.
  const uint64_t off = uint64_t{1} << 20;
  return ((static_cast<uint64_t>(block.x() + off) & 0x1fffff) << 42) |
         ((static_cast<uint64_t>(block.y() + off) & 0x1fffff) << 21) |
         (static_cast<uint64_t>(block.z() + off) & 0x1fffff);
}

PointCloudWorld::PointCloudWorld(const std::vector<Eigen::Vector3f>& points,
                                 const PointCloudWorldOptions& options)
    : options_(options), kdtree_(std::make_unique<KdTree>()) {
  lo_ = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  hi_ = -lo_;
  const double v = options_.voxel_m;
  for (const Eigen::Vector3f& pf : points) {
    if (!pf.allFinite()) continue;
    const Eigen::Vector3d p = pf.cast<double>();
    ++num_points_;
    lo_ = lo_.cwiseMin(p);
    hi_ = hi_.cwiseMax(p);
    const Eigen::Vector3i voxel((p / v).array().floor().cast<int>());
    const Eigen::Vector3i block(floorDiv(voxel.x(), kBlockEdge), floorDiv(voxel.y(), kBlockEdge),
                                floorDiv(voxel.z(), kBlockEdge));
    auto [it, inserted] =
        block_index_.emplace(blockKey(block), static_cast<uint32_t>(blocks_.size()));
    if (inserted) blocks_.push_back(BlockBits{});
    const Eigen::Vector3i l = voxel - kBlockEdge * block;
    const int bit = l.x() + kBlockEdge * (l.y() + kBlockEdge * l.z());
    uint64_t& word = blocks_[it->second][bit / 64];
    const uint64_t mask = uint64_t{1} << (bit % 64);
    if (!(word & mask)) {
      word |= mask;
      ++num_voxels_;
      surface_.push_back(((voxel.cast<double>().array() + 0.5) * v).matrix().cast<float>());
    }
  }
  if (num_points_ == 0) throw std::invalid_argument("point cloud world: no finite point");
  kdtree_->cloud->reserve(surface_.size());
  for (const Eigen::Vector3f& s : surface_)
    kdtree_->cloud->push_back(pcl::PointXYZ(s.x(), s.y(), s.z()));
  kdtree_->tree.setInputCloud(kdtree_->cloud);
}

PointCloudWorld::~PointCloudWorld() = default;

std::unique_ptr<PointCloudWorld> PointCloudWorld::loadPcd(const std::string& path,
                                                          const PointCloudWorldOptions& options) {
  const std::vector<Eigen::Vector3f> points = readPcdPoints(path);
  try {
    return std::make_unique<PointCloudWorld>(points, options);
  } catch (const std::invalid_argument&) {
    throw std::runtime_error("PCD file " + path + " holds no finite point");
  }
}

const PointCloudWorld::BlockBits* PointCloudWorld::findBlock(const Eigen::Vector3i& block) const {
  auto it = block_index_.find(blockKey(block));
  return it == block_index_.end() ? nullptr : &blocks_[it->second];
}

bool PointCloudWorld::voxelOccupied(const Eigen::Vector3i& voxel) const {
  const Eigen::Vector3i block(floorDiv(voxel.x(), kBlockEdge), floorDiv(voxel.y(), kBlockEdge),
                              floorDiv(voxel.z(), kBlockEdge));
  const BlockBits* bits = findBlock(block);
  if (!bits) return false;
  const Eigen::Vector3i l = voxel - kBlockEdge * block;
  const int bit = l.x() + kBlockEdge * (l.y() + kBlockEdge * l.z());
  return ((*bits)[bit / 64] >> (bit % 64)) & 1u;
}

double PointCloudWorld::castOne(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                double max_range) const {
  // Two levels: walk the blocks, and the voxels only inside blocks that hold points.
  const double v = options_.voxel_m;
  const double block_edge = kBlockEdge * v;
  double hit = -1.0;
  detail::traverseCells(
      origin, dir, 0.0, max_range, block_edge,
      [&](const Eigen::Vector3i& block, double t_in, double t_out) {
        const BlockBits* bits = findBlock(block);
        if (!bits) return true;
        const Eigen::Vector3i first = kBlockEdge * block;
        detail::traverseCells(
            origin, dir, t_in, t_out, v, [&](const Eigen::Vector3i& voxel, double vt_in, double) {
              // Round-off at the block boundary may name a voxel just outside: clamp it in.
              const Eigen::Vector3i l = (voxel - first).cwiseMax(0).cwiseMin(kBlockEdge - 1);
              const int bit = l.x() + kBlockEdge * (l.y() + kBlockEdge * l.z());
              if (((*bits)[bit / 64] >> (bit % 64)) & 1u) {
                hit = vt_in;
                return false;
              }
              return true;
            });
        return hit < 0.0;
      });
  return hit;
}

void PointCloudWorld::raycast(const Eigen::Vector3d& origin,
                              const std::vector<Eigen::Vector3d>& dirs, double max_range,
                              std::vector<double>* ranges) const {
  ranges->resize(dirs.size());
  for (size_t i = 0; i < dirs.size(); ++i) (*ranges)[i] = castOne(origin, dirs[i], max_range);
}

double PointCloudWorld::clearance(const Eigen::Vector3d& p) const {
  std::vector<int> index(1);
  std::vector<float> d2(1);
  const pcl::PointXYZ q(static_cast<float>(p.x()), static_cast<float>(p.y()),
                        static_cast<float>(p.z()));
  if (kdtree_->tree.nearestKSearch(q, 1, index, d2) < 1) {
    return std::numeric_limits<double>::infinity();
  }
  return std::sqrt(static_cast<double>(d2[0]));
}

double PointCloudWorld::shortestPathLength(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                           double radius) const {
  // A grid over the points, a and b with a margin for going around, clipped to the bound box;
  // coarsened if it would exceed ~8 M cells (the A* keeps 12 bytes per cell).
  const double margin = 2.0 + radius;
  Eigen::Vector3d lo = lo_.cwiseMin(a).cwiseMin(b) - Eigen::Vector3d::Constant(margin);
  Eigen::Vector3d hi = hi_.cwiseMax(a).cwiseMax(b) + Eigen::Vector3d::Constant(margin);
  lo = lo.cwiseMax(options_.bound_min_m);
  hi = hi.cwiseMin(options_.bound_max_m);
  if ((hi - lo).minCoeff() <= 0.0) return -1.0;
  VoxelGrid grid = boundSearchGrid(lo, hi, options_.bound_grid_m);
  for (const Eigen::Vector3f& s : surface_) {
    const Eigen::Vector3i local = grid.localIndexOf(s.cast<double>());
    if (grid.inWindow(local)) grid.set(local, Occupancy::kOccupied);
  }
  grid.setInflationRadius(radius);
  return gridShortestPath(grid, a, b, lo, hi);
}

std::string PointCloudWorld::describe() const {
  std::ostringstream out;
  out << "point cloud of " << num_points_ << " points (" << num_voxels_ << " voxels of "
      << options_.voxel_m << " m)";
  return out.str();
}

}  // namespace mmh::sim
