// Whether the seeds of the safe flight corridor are free: straight segments and triangles of
// the grid's unblocked cells (cells the escape zone frees count as free), optionally keeping a
// clearance from the blocked cells.
#pragma once

#include <Eigen/Core>

#include "mmh/common/voxel_grid.hpp"
#include "mmh/som/obstacle_points.hpp"

namespace mmh::som {

// The cell containing p is blocked and not freed by the escape zone.
bool seedBlockedAt(const VoxelGrid& grid, const Eigen::Vector3d& p, const EscapeZone& escape);

// The segment [a, b] crosses no blocked cell (samples a quarter voxel apart). With a clearance
// (m, less than half a voxel), the axis-aligned box of that half-width around each sample
// touches none either.
bool segmentVisible(const VoxelGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                    const EscapeZone& escape, double clearance_m = 0.0);

// The triangle a, b, c is free: the segments from c to points along [a, b] at most half a voxel
// apart are visible (with the clearance).
bool triangleVisible(const VoxelGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                     const Eigen::Vector3d& c, const EscapeZone& escape, double clearance_m = 0.0);

}  // namespace mmh::som
