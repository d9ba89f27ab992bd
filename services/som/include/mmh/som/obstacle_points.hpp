// Obstacle points for the corridor: centres of blocked cells (inside the inflated obstacles) of
// the voxel grid in a small world box. Only cells on the surface of the blocked set are needed
// to grow a polytope; a scan of the polytope's own cells then proves that no blocked centre at
// all lies inside it.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "mmh/common/voxel_grid.hpp"
#include "mmh/som/polytope.hpp"

namespace mmh::som {

// Blocked cells that are not occupied and whose centre lies within `radius` of `center` are
// treated as free: the margin a start inside the inflated zone must be allowed to leave.
struct EscapeZone {
  EscapeZone() = default;
  EscapeZone(const Eigen::Vector3d& center_m, double radius_m, double min_distance_m = 0.0)
      : center(center_m), radius(radius_m), min_distance(min_distance_m) {}

  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = -1.0;  // < 0: none
  // Only cells whose centres keep this distance from the occupied cells (and the start's own
  // cell) are free: the way out of the margin leads outwards (mmh::escapeMinDistance).
  double min_distance = 0.0;
  // Whether the (inflated, not occupied) cell `local` with centre c is free for the escape.
  bool frees(const VoxelGrid& grid, const Eigen::Vector3i& local, const Eigen::Vector3d& c) const;

 private:
  // The distance test of each cell asked about, by linear index: the corridor asks about the same
  // few hundred cells round the start again for every seed box and visibility test. Valid for
  // one grid and the fields as first asked with: a zone lives for one plan.
  mutable std::unordered_map<int64_t, bool> keeps_distance_;
};

// A byte mask of the blocked cells whose centres lie in a world box (plus a one-cell border, so
// that the surface test needs no bounds checks; cells outside the window count as not
// blocked), built once per seed and used for both queries below.
class BlockedMask {
 public:
  // False if no cell centre lies in [lo, hi]. Surface cells whose centres lie within
  // check_inflation_m of an occupied cell (a smaller margin that another check blocks whole
  // cells by; 0: none) also give points on their faces towards unblocked 6-neighbours, moved
  // check_face_clearance_m off the cell into the neighbour. With check_whole_cells every cell
  // within that margin gives points that far off all its outside towards the neighbours (of 26)
  // outside the margin: the 3 x 3 points of each such face, and the edge or corner it shares
  // with a neighbour that touches it only there. Many more points, fewer cut corners.
  bool build(const VoxelGrid& grid, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
             const EscapeZone& escape, double check_inflation_m = 0.0,
             double check_face_clearance_m = 0.0, bool check_whole_cells = false);
  // Centres of the blocked cells with at least one 6-neighbour that is not blocked, and the
  // face points of build.
  void surfacePoints(std::vector<Eigen::Vector3d>* out) const;
  // Centres of all blocked cells strictly inside `poly` (a . x < b for every face).
  void pointsInside(const Polytope& poly, std::vector<Eigen::Vector3d>* out) const;

 private:
  void addCheckFaces(const VoxelGrid& grid, const Eigen::Vector3i& first, double check_inflation_m,
                     double clearance_m);
  void addCheckCellFences(const VoxelGrid& grid, const Eigen::Vector3i& first,
                          double check_inflation_m, double clearance_m);
  Eigen::Vector3d centerOf(int x, int y, int z) const {
    return corner_ + Eigen::Vector3d(x, y, z) * res_;
  }
  std::vector<uint8_t> mask_;  // (n + 2) cells per axis, x fastest
  // Centres of the faces between a cell the escape frees (not the start's own) and a blocked
  // 6-neighbour: obstacle points too (see build).
  std::vector<Eigen::Vector3d> escape_faces_;
  // Points on the faces between a surface cell within the check inflation and an unblocked
  // 6-neighbour, moved off the cell (see build).
  std::vector<Eigen::Vector3d> check_faces_;
  std::vector<uint8_t> within_check_;  // laid out like mask_: cells within the check margin
  Eigen::Vector3i n_ = Eigen::Vector3i::Zero();       // cells of the box per axis
  Eigen::Vector3d corner_ = Eigen::Vector3d::Zero();  // centre of box cell (0, 0, 0)
  double res_ = 0.1;
  int64_t sy_ = 0, sz_ = 0;  // strides of the bordered mask
  struct FaceRow {
    double base, dy, dz, inv;
    int sign;
  };
  mutable std::vector<FaceRow> faces_;  // scratch of pointsInside
  mutable std::vector<uint8_t> row_;    // scratch of surfacePoints
};

// Convenience wrappers (one mask each).
void blockedSurfacePoints(const VoxelGrid& grid, const Eigen::Vector3d& lo,
                          const Eigen::Vector3d& hi, const EscapeZone& escape,
                          std::vector<Eigen::Vector3d>* out);
void blockedPointsInside(const VoxelGrid& grid, const Eigen::Vector3d& lo,
                         const Eigen::Vector3d& hi, const Polytope& poly, const EscapeZone& escape,
                         std::vector<Eigen::Vector3d>* out);

// Whether an occupied cell lies at one of `offsets` (VoxelGrid::offsetsWithin) from cell
// `local`: the grid's inflation rule for another radius, without an inflated copy of the grid.
bool withinInflation(const VoxelGrid& grid, const Eigen::Vector3i& local,
                     const std::vector<Eigen::Vector3i>& offsets);

// Index range (inclusive, local cell indices) of the cells whose centres lie in [lo, hi],
// clamped to the window; false if empty.
bool cellRange(const VoxelGrid& grid, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
               Eigen::Vector3i* first, Eigen::Vector3i* last);

}  // namespace mmh::som
