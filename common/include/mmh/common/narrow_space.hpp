// Narrow-space test of the paper (Sec. III.B, "BothSideJudge"): probe both sides of a short
// segment along its normals; obstacles on both sides of either normal mean a narrow passage.
// Used by awareness (on the sensing ray) and by EAM (on its A* path).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mmh/common/voxel_grid.hpp"

namespace mmh {

// True when, from the midpoint of [a, b], occupied cells are found within probe_dist_m on both
// the left and the right (horizontal normal), or both above and below (vertical normal).
// Probes look at the uninflated occupancy; unknown counts as free.
bool bothSidesBlocked(const VoxelGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                      double probe_dist_m);

// Runs bothSidesBlocked on consecutive samples (one resolution apart) along a polyline.
// Returns true at the first narrow pair; *where receives its midpoint if given.
bool isPathNarrow(const VoxelGrid& grid, const std::vector<Eigen::Vector3d>& path,
                  double probe_dist_m, Eigen::Vector3d* where = nullptr);

}  // namespace mmh
