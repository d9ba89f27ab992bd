// Independent check of an EAM answer before it is sent: it looks only at the polynomial pieces
// and the grid, never at the optimiser's state.
#pragma once

#include <Eigen/Core>
#include <string>

#include "mmh/common/trajectory.hpp"
#include "mmh/common/voxel_grid.hpp"
#include "mmh/eam/eam_params.hpp"

namespace mmh::eam {

struct Verification {
  bool ok = false;
  std::string why;                        // first failed check
  bool collision = false;                 // it failed on an obstacle
  double max_speed = 0.0, max_acc = 0.0;  // exact maxima of the pieces
};

// Checks, in order: finite pieces; start state (position, velocity, acceleration) and end at the
// target at rest, within 1e-6; no sample inside an occupied cell and none inside the inflated
// margin (except while a start that lies in the margin leaves it within start_escape_radius_m),
// samples at most a quarter voxel apart; exact max speed / acceleration within
// (1 + limit_tolerance_ratio) of the limits; inside the geofence (1 cm tolerance).
Verification verifyTrajectory(const Trajectory& traj, const VoxelGrid& grid,
                              const KinematicState& start, const Eigen::Vector3d& target,
                              const EamParams& params);

}  // namespace mmh::eam
