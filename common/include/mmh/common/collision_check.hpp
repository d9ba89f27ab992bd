// Collision checks of points, segments and trajectories against a VoxelGrid. "Blocked" means
// inside the inflated obstacles; unknown space counts as free (the paper's convention).
#pragma once

#include <Eigen/Core>
#include <functional>
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

// Samples the segment at most resolution/4 apart (end points included); a sample is also
// blocked where `also_blocked` (if given) is true.
bool isSegmentFree(const VoxelGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                   CollisionLayer layer = CollisionLayer::kInflated,
                   const std::function<bool(const Eigen::Vector3d&)>& also_blocked = {});

// Time step of trajectory collision checks: samples at most resolution/4 apart in space at the
// trajectory's exact maximum speed. A check that must find the same cells as another samples
// at the same times.
double collisionSampleStep(const VoxelGrid& grid, const Trajectory& traj);

// First time in [t0, t1] (trajectory time) at which the trajectory is blocked, sampling every
// collisionSampleStep from t0. nullopt when free.
std::optional<double> firstCollisionTime(const VoxelGrid& grid, const Trajectory& traj, double t0,
                                         double t1,
                                         CollisionLayer layer = CollisionLayer::kInflated);

// Distance from p to the centre of the nearest occupied cell, looking no further than limit_m
// (limit_m when none is nearer). Unknown cells and cells outside the window count as free.
double occupiedDistance(const VoxelGrid& grid, const Eigen::Vector3d& p, double limit_m);

// A start inside the inflated margin may leave it ("escape"), but only outwards: no point of
// the way out may come nearer to the occupied cells than the start itself or than floor_m,
// whichever is less. This is that distance (the start's, capped at floor_m); a point p keeps it
// when occupiedDistance(grid, p, d) >= d - kEscapeDepthTolerance. Without the rule, a vehicle
// next to an obstacle was re-planned along it, a little nearer each time, until it touched it.
double escapeMinDistance(const VoxelGrid& grid, const Eigen::Vector3d& start, double floor_m);
constexpr double kEscapeDepthTolerance = 0.02;  // m
inline bool keepsEscapeDistance(const VoxelGrid& grid, const Eigen::Vector3d& p,
                                double min_distance_m, double tolerance_m = kEscapeDepthTolerance) {
  return occupiedDistance(grid, p, min_distance_m) >= min_distance_m - tolerance_m;
}

// A start inside the margin may leave it anywhere within radius_m of the start (keeping the
// escape distance): the escape zone lasts until the trajectory's first sample (every step_s)
// farther than that from its start, or its end.
double escapeZoneEnd(const Trajectory& traj, double radius_m, double step_s);
// The escape's walk over [t0, t1) every step_s: the first sample inside the margin that does not
// keep min_distance_m (keepsEscapeDistance), or nothing.
std::optional<double> firstEscapeTooDeep(const VoxelGrid& grid, const Trajectory& traj, double t0,
                                         double t1, double step_s, double min_distance_m,
                                         double tolerance_m);

// The first forced_until_s of a trajectory are fixed by its start state: no plan can leave the way
// the start carries the vehicle by more than a few centimetres (EamParams::start_forced_s). A
// sample there in the inflated margin (not in an occupied cell: the caller's check) is no
// collision when it keeps the escape distance (forced_until_s 0: never).
inline bool forcedByStart(const VoxelGrid& grid, const Eigen::Vector3d& p, double t_s,
                          double forced_until_s, double min_distance_m,
                          double tolerance_m = kEscapeDepthTolerance) {
  return forced_until_s > 0.0 && t_s <= forced_until_s &&
         keepsEscapeDistance(grid, p, min_distance_m, tolerance_m);
}

}  // namespace mmh
