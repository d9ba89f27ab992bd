// Obstacle points for the corridor: centres of blocked cells (inside the inflated obstacles) of
// the voxel grid in a small world box. Only cells on the surface of the blocked set are needed
// to grow a polytope; a scan of the polytope's own cells then proves that no blocked centre at
// all lies inside it.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mmh/common/voxel_grid.hpp"
#include "mmh/som/polytope.hpp"

namespace mmh::som {

// Blocked cells that are not occupied and whose centre lies within `radius` of `center` are
// treated as free: the margin a start inside the inflated zone must be allowed to leave.
struct EscapeZone {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = -1.0;  // < 0: none
};

// Centres of the blocked cells whose centre lies in [lo, hi] and that have at least one
// 6-neighbour that is not blocked (cells outside the window count as not blocked).
void blockedSurfacePoints(const VoxelGrid& grid, const Eigen::Vector3d& lo,
                          const Eigen::Vector3d& hi, const EscapeZone& escape,
                          std::vector<Eigen::Vector3d>* out);

// Centres of all blocked cells that lie in [lo, hi] and strictly inside `poly` (a . x < b for
// every face), found by intersecting each x-row of cells with the polytope.
void blockedPointsInside(const VoxelGrid& grid, const Eigen::Vector3d& lo,
                         const Eigen::Vector3d& hi, const Polytope& poly, const EscapeZone& escape,
                         std::vector<Eigen::Vector3d>* out);

// Index range (inclusive, local cell indices) of the cells whose centres lie in [lo, hi],
// clamped to the window; false if empty.
bool cellRange(const VoxelGrid& grid, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
               Eigen::Vector3i* first, Eigen::Vector3i* last);

}  // namespace mmh::som
