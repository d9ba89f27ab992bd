// ESDF-free collision information for EAM (after EGO-Planner): find the stretches where the
// B-spline runs through inflated obstacles, and turn each one, with an A* path around it, into
// {p, v} anchor pairs for the control points that shape it.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mmh/common/voxel_grid.hpp"
#include "mmh/eam/bspline_cost.hpp"
#include "mmh/eam/uniform_bspline.hpp"

namespace mmh::eam {

struct CurveSample {
  double t = 0.0;   // curve time
  int segment = 0;  // knot interval (depends on control points segment .. segment + 3)
  double s = 0.0;   // local parameter in [0, 1) within the interval
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
};

// One run of consecutive blocked samples of the curve.
struct CollisionStretch {
  std::vector<CurveSample> blocked;
  Eigen::Vector3d before = Eigen::Vector3d::Zero();  // free curve point just before (or start)
  Eigen::Vector3d after = Eigen::Vector3d::Zero();   // free curve point just after
  double t_before = 0.0, t_after = 0.0;              // their curve times
  bool from_start = false;  // the run begins at the start (start inside the inflated margin)
};

// Samples the curve at most step_m apart (a quarter voxel, as the final verification does, or
// finer). A start inside the inflated margin (not in an occupied cell) may leave it: leading
// blocked samples within escape_radius_m of the start that keep escape_min_distance_m from the
// occupied cells (mmh::keepsEscapeDistance) are not collisions (the same rule as the
// verification). Nor are margin samples (not occupied) up to forced_until_s after the start that
// keep escape_min_distance_m: there the start state fixes the way (EamParams::start_forced_s).
std::vector<CollisionStretch> findCollisionStretches(const UniformBspline& spline,
                                                     const VoxelGrid& grid, double escape_radius_m,
                                                     double step_m,
                                                     double escape_min_distance_m = 0.0,
                                                     double forced_until_s = 0.0);

// Adds anchor pairs for the free control points [first_free, last_free] that shape the
// stretch: for each, a blocked probe point x (the control point itself when it is blocked, else
// the blocked curve sample it weighs most on) and the travel direction there define a plane
// that cuts the guide path (A*) at g; v = (g - x)/|g - x|, and p is the last free point met
// going from g towards x (the obstacle surface); its clearance is clearance_m, or half the free
// width beyond p along v when that is less. A pair too similar to an existing one of the
// same control point is not added; if the control point already keeps that pair's clearance
// (the curve still hits although the plane is respected), the pair's clearance grows by half a
// voxel instead, within the free width. Returns the number of pairs added or widened.
int addAnchorPairs(const CollisionStretch& stretch, const std::vector<Eigen::Vector3d>& guide_path,
                   const UniformBspline& spline, const VoxelGrid& grid, int first_free,
                   int last_free, double clearance_m, PairSet& pairs);

}  // namespace mmh::eam
