// Shortest collision-free path lengths, known only to the simulator, and the time bound of
// docs/benchmark.md computed from them: rest to rest at v_max / a_max along the shortest path.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mmh/common/voxel_grid.hpp"

namespace mmh::sim {

struct Disc {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 0.0;
};

// Exact length of the shortest path from a to b in the plane that does not enter the interior
// of any disc: Dijkstra on the visibility graph of tangent segments (point-disc and disc-disc
// bitangents) and free boundary arcs. Only discs that can touch a path of length <= L are
// considered (an ellipse around a and b, grown until the result fits in it). Returns a negative
// value if a or b is inside a disc or no path exists. `path`, if given, receives the tangent
// points of the shortest path (arcs between them are not sampled).
double shortestPathAmongDiscs(const std::vector<Disc>& discs, const Eigen::Vector2d& a,
                              const Eigen::Vector2d& b,
                              std::vector<Eigen::Vector2d>* path = nullptr);

// Shortest path on a voxel grid whose inflation marks where the vehicle centre may not go:
// 26-connected A* (common/grid_astar.hpp) restricted to [min_bound, max_bound], then shortened by
// line of sight. An approximation (grid resolution); negative if no path is found.
double gridShortestPath(const VoxelGrid& inflated_grid, const Eigen::Vector3d& a,
                        const Eigen::Vector3d& b, const Eigen::Vector3d& min_bound,
                        const Eigen::Vector3d& max_bound);

// An empty grid over [lo, hi] for gridShortestPath, at grid_m or, coarsened by steps of 1.25,
// at the first resolution that keeps it within ~8 M cells (the A* keeps 12 bytes per cell).
VoxelGrid boundSearchGrid(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double grid_m);

}  // namespace mmh::sim
