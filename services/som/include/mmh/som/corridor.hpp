// Safe flight corridor: a chain of convex polytopes along the shortened A* path, each grown by
// FIRI-style inflation from a seed sub-segment of the path and free of every blocked (inflated
// obstacle) cell centre, consecutive ones overlapping, redundant ones removed.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mmh/common/voxel_grid.hpp"
#include "mmh/som/ellipsoid.hpp"
#include "mmh/som/obstacle_points.hpp"
#include "mmh/som/params.hpp"
#include "mmh/som/polytope.hpp"
#include "mmh/som/polytope_inflation.hpp"

namespace mmh::som {

struct Corridor {
  std::vector<Polytope> polytopes;
  // junctions[i] lies in polytopes[i] and polytopes[i + 1] (a point of the path, chosen at
  // least the junction margin inside where the path allows).
  std::vector<Eigen::Vector3d> junctions;
  // ellipsoids[i] lies in polytopes[i] (the metric its last faces were placed with); empty when
  // the corridor was made by hand. Only a shortcut for the optimiser's corridor penalty.
  std::vector<Ellipsoid> ellipsoids;
  // Box that bounds every polytope (geofence within the map window).
  Eigen::Vector3d bound_lo = Eigen::Vector3d::Zero(), bound_hi = Eigen::Vector3d::Zero();
  int polytopes_built = 0;  // before redundant ones were removed
  int surface_points = 0;   // obstacle points used, summed over the polytopes built
};

// A corridor face may pass through a seed end point (it is a face offset by 1e-6 m from an
// obstacle point), so containment of the start and target is tested with this tolerance.
constexpr double kCorridorContainTolerance = 1e-5;

class CorridorBuilder {
 public:
  // `path` runs from the start to the target; consecutive points are joined by free segments.
  // The corridor is bounded by [bound_lo, bound_hi] (which must contain the path). With a
  // moving start, the first polytope also covers the braking distance at max_acc_mps2 along
  // start_velocity where that is free. Returns false with a reason in `why` if no corridor
  // could be built.
  bool build(const VoxelGrid& grid, const std::vector<Eigen::Vector3d>& path,
             const Eigen::Vector3d& bound_lo, const Eigen::Vector3d& bound_hi,
             const EscapeZone& escape, const CorridorParams& params, Corridor* out,
             std::string* why, const Eigen::Vector3d& start_velocity = Eigen::Vector3d::Zero(),
             double max_acc_mps2 = 0.0);

 private:
  PolytopeInflator inflator_;
  BlockedMask mask_;
  std::vector<Eigen::Vector3d> points_, extra_;
};

// Polyline with arc-length access.
class PathCurve {
 public:
  explicit PathCurve(const std::vector<Eigen::Vector3d>& points);
  double length() const { return cumulative_.back(); }
  int numSegments() const { return static_cast<int>(points_.size()) - 1; }
  // Segment containing arc length s (the later one at a vertex, except at the very end).
  int segmentAt(double s) const;
  double segmentStart(int k) const { return cumulative_[k]; }
  double segmentEnd(int k) const { return cumulative_[k + 1]; }
  // End of the segment that leads on from arc length s: the next segment's when s lies on a
  // vertex up to rounding (an arc length found by stepping back from farther ahead may fall a
  // hair short of the vertex, where segmentAt still gives the segment ending there).
  double segmentEndAfter(double s) const;
  Eigen::Vector3d pointAt(double s) const;
  const Eigen::Vector3d& vertex(int k) const { return points_[k]; }

 private:
  std::vector<Eigen::Vector3d> points_;
  std::vector<double> cumulative_;
};

}  // namespace mmh::som
