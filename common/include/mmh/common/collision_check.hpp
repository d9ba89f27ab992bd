// Collision checks of points, segments and trajectories against a VoxelGrid. "Blocked" means
// inside the inflated obstacles; unknown space counts as free (the paper's convention).
#pragma once

#include <Eigen/Core>
#include <optional>

#include "mmh/common/trajectory.hpp"
#include "mmh/common/voxel_grid.hpp"

namespace mmh {

enum class CollisionLayer {
  kInflated,  // cells within the inflation radius of an occupied cell
  kOccupied,  // occupied cells only (the uninflated map)
};

bool isPointBlocked(const VoxelGrid& grid, const Eigen::Vector3d& p,
                    CollisionLayer layer = CollisionLayer::kInflated);

// Samples the segment at most resolution/4 apart (end points included).
bool isSegmentFree(const VoxelGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                   CollisionLayer layer = CollisionLayer::kInflated);

// First time in [t0, t1] (trajectory time) at which the trajectory is blocked, sampling so that
// consecutive samples are at most resolution/4 apart in space. nullopt when free.
std::optional<double> firstCollisionTime(const VoxelGrid& grid, const Trajectory& traj, double t0,
                                         double t1,
                                         CollisionLayer layer = CollisionLayer::kInflated);

}  // namespace mmh
