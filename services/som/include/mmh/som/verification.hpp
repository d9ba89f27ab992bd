// Independent check of a SOM trajectory before it is answered: it looks only at the trajectory
// itself, the map and the corridor, never at the optimiser's internals (exact maxima of speed
// and acceleration, fine sampling against the uninflated map and the polytopes).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mmh/common/trajectory.hpp"
#include "mmh/common/voxel_grid.hpp"
#include "mmh/som/corridor.hpp"
#include "mmh/som/params.hpp"

namespace mmh::som {

struct VerifyReport {
  bool ok = false;
  std::string failure;  // what failed first, empty if ok
  double max_speed = 0.0, max_acceleration = 0.0;
  double max_corridor_violation_m = 0.0;  // worst distance outside the corridor over the samples
  int samples = 0;
};

// Checks, in this order: finite trajectory; starts exactly at `start` and ends at `target` at
// rest; exact max speed / acceleration within (1 + tolerance) of the limits; samples at most a
// quarter voxel apart none of which lies in an occupied voxel of the (uninflated) map and each
// of which lies in its piece's polytope, or in some polytope of the corridor, within the
// corridor tolerance.
VerifyReport verifyTrajectory(const Trajectory& traj, const KinematicState& start,
                              const Eigen::Vector3d& target, const VoxelGrid& grid,
                              const Corridor& corridor, const std::vector<int>& piece_polytope,
                              double max_vel_mps, double max_acc_mps2, const VerifyParams& params,
                              double escape_min_distance_m = 0.0);

// Whether `traj` enters a cell whose centre lies within check_inflation_m of an occupied cell -
// the cells the arbiter's own collision check blocks - after it has left those it starts in (a
// start inside that margin may leave it). Sampled as the arbiter samples its check.
bool entersCheckMargin(const Trajectory& traj, const VoxelGrid& grid, double check_inflation_m);

}  // namespace mmh::som
