// The stuck detector's last resort: a slow way back along positions the vehicle has flown. When
// no mode can plan out of a spot (a gap that the mapped outlines of trunks have closed behind it,
// a pocket whose every exit lies within the planners' margin), the way it came is still one the
// airframe has passed.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "mmh/common/trajectory.hpp"
#include "mmh/common/voxel_grid.hpp"

namespace mmh::arbiter {

// A minimum-jerk trajectory from `start` through `route` (route[0] is the start's position) to
// rest at its last point, timed at about speed_mps and slowed until it keeps max_vel_mps and
// max_acc_mps2. Nothing for a route shorter than two points or a start it cannot keep the
// limits from.
std::optional<Trajectory> retraceTrajectory(const KinematicState& start,
                                            const std::vector<Eigen::Vector3d>& route,
                                            double speed_mps, double max_vel_mps,
                                            double max_acc_mps2);

// True when every point of `t` (every step_s) keeps min_distance_m from the occupied cells'
// centres of `grid` (keepsEscapeDistance, with its tolerance), though it may pass inside the
// planners' margin.
bool keepsOffOccupied(const VoxelGrid& grid, const Trajectory& t, double min_distance_m,
                      double step_s);

}  // namespace mmh::arbiter
