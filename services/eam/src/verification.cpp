#include "mmh/eam/verification.hpp"

#include "mmh/common/collision_check.hpp"
#include "mmh/common/geofence.hpp"
#include "mmh/common/trajectory_verifier.hpp"

#include <algorithm>
#include <cmath>

namespace mmh::eam {

Verification verifyTrajectory(const Trajectory& traj, const VoxelGrid& grid,
                              const KinematicState& start, const Eigen::Vector3d& target,
                              const EamParams& params) {
  // The shared verifier (mmh/common/trajectory_verifier.hpp) with EAM's tolerances: start and
  // end within 1e-6, both layers with the escape from a start in the margin, the geofence with
  // 1 cm, the limits (closed-form maxima of the cubic pieces) after the samples, so that a
  // curve that collides is reported as a collision (a restart may help it).
  VerifierOptions o;
  o.check_start = true;
  o.start = start;
  o.start_position_tol_m = o.start_velocity_tol_mps = o.start_acceleration_tol_mps2 = 1e-6;
  o.check_end = true;
  o.target = target;
  o.end_position_tol_m = o.rest_velocity_tol_mps = o.rest_acceleration_tol_mps2 = 1e-6;
  o.check_limits = true;
  o.max_vel_mps = params.max_vel_mps;
  o.max_acc_mps2 = params.max_acc_mps2;
  o.limit_relative_tol = params.limit_tolerance_ratio;
  o.maxima = MaximaMethod::kCubicClosedForm;
  o.limits_after_samples = true;
  o.check_geofence = true;
  const Geofence fence = fenceForStart(Geofence{params.geofence_min, params.geofence_max},
                                       start.position, params.arbiter_geofence_tolerance_m);
  o.geofence_min = fence.min_m;
  o.geofence_max = fence.max_m;
  o.geofence_tol_m = 0.01;
  o.grid = &grid;
  o.check_inflated = true;
  o.escape_radius_m = params.start_escape_radius_m;
  o.escape_min_distance_m =
      escapeMinDistance(grid, start.position, params.start_escape_clearance_m);
  o.escape_from_first_sample = true;
  o.forced_until_s = params.start_forced_s;
  o.min_time_step_s = 1e-5;
  o.cubic_fast_path = true;
  const VerifyResult v = mmh::verifyTrajectory(traj, o);
  Verification r;
  r.ok = v.ok;
  r.why = v.why;
  r.collision = v.collision();
  r.max_speed = v.max_speed;
  r.max_acc = v.max_acc;
  return r;
}

}  // namespace mmh::eam
