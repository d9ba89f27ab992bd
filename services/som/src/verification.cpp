#include "mmh/som/verification.hpp"

#include "mmh/common/collision_check.hpp"
#include "mmh/common/trajectory_verifier.hpp"
#include "mmh/som/obstacle_points.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <sstream>

namespace mmh::som {
namespace {

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

}  // namespace

VerifyReport verifyTrajectory(const Trajectory& traj, const KinematicState& start,
                              const Eigen::Vector3d& target, const VoxelGrid& grid,
                              const Corridor& corridor, const std::vector<int>& piece_polytope,
                              double max_vel_mps, double max_acc_mps2, const VerifyParams& params,
                              double escape_min_distance_m) {
  VerifyReport r;
  auto fail = [&](const std::string& why) {
    r.ok = false;
    r.failure = why;
    return r;
  };
  if (traj.empty() || !traj.isFinite()) return fail("trajectory is empty or not finite");
  if (static_cast<int>(piece_polytope.size()) != traj.numPieces())
    return fail("piece-to-polytope map does not match the trajectory");
  // The shared verifier (mmh/common/trajectory_verifier.hpp) with SOM's tolerances: the start
  // exactly, the end within the endpoint tolerance and at rest, the limits before the samples,
  // only the occupied layer (the corridor keeps the margin) and, on top, the corridor.
  VerifierOptions o;
  o.check_start = true;
  o.start = start;
  o.start_position_tol_m = o.start_velocity_tol_mps = o.start_acceleration_tol_mps2 = 1e-9;
  o.check_end = true;
  o.target = target;
  o.end_position_tol_m = params.endpoint_tolerance_m;
  o.rest_velocity_tol_mps = o.rest_acceleration_tol_mps2 = 1e-3;
  o.check_limits = true;
  o.max_vel_mps = max_vel_mps;
  o.max_acc_mps2 = max_acc_mps2;
  o.limit_relative_tol = params.limit_tolerance;
  o.maxima = MaximaMethod::kStationaryPoints;
  o.grid = &grid;
  o.check_inflated = false;
  o.escape_min_distance_m = escape_min_distance_m;
  o.escape_from_first_sample = false;  // only a start that lies in the margin escapes
  o.min_time_step_s = 1e-4;
  o.sample_check = [&](int piece, double, const Eigen::Vector3d& p, std::string* why) {
    // In its piece's polytope, or in some polytope of the corridor, within the tolerance.
    double v = corridor.polytopes.at(piece_polytope[piece]).maxViolation(p);
    if (v > params.corridor_tolerance_m) {
      for (const Polytope& other : corridor.polytopes) v = std::min(v, other.maxViolation(p));
    }
    r.max_corridor_violation_m = std::max(r.max_corridor_violation_m, v);
    if (v <= params.corridor_tolerance_m) return true;
    *why = "leaves the corridor by " + fmt(v) + " m in piece " + std::to_string(piece);
    return false;
  };
  const VerifyResult v = mmh::verifyTrajectory(traj, o);
  r.max_speed = v.max_speed;
  r.max_acceleration = v.max_acc;
  r.samples = v.samples;
  if (!v.ok) return fail(v.why);
  r.ok = true;
  return r;
}

bool entersCheckMargin(const Trajectory& traj, const VoxelGrid& grid, double check_inflation_m) {
  if (traj.empty()) return false;
  const std::vector<Eigen::Vector3i> offsets =
      VoxelGrid::offsetsWithin(check_inflation_m, grid.resolution());
  // The sample times of the arbiter's check (mmh::firstCollisionTime), so that both find the
  // same cells: a corner cut a few millimetres deep is met by one sample or by none.
  const double dt = collisionSampleStep(grid, traj);
  const double end = traj.duration();
  // A cell within the check margin of an occupied cell is within the grid's own margin too when
  // that is no smaller: the grid's blocked counts clear most cells without a look round them.
  const bool grid_margin_covers = check_inflation_m <= grid.inflationRadius();
  bool leaving_start = true;
  Eigen::Vector3i last(INT32_MIN, INT32_MIN, INT32_MIN);
  for (double s = 0.0;; s += dt) {
    const double at = std::min(s, end);
    const Eigen::Vector3i cell = grid.localIndexOf(traj.position(at));
    if (cell != last) {
      last = cell;
      const bool blocked = !(grid_margin_covers && grid.inWindow(cell) && !grid.isBlocked(cell)) &&
                           withinInflation(grid, cell, offsets);
      if (leaving_start)
        leaving_start = blocked;
      else if (blocked)
        return true;
    }
    if (at >= end) break;
  }
  return false;
}

}  // namespace mmh::som
