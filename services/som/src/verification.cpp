#include "mmh/som/verification.hpp"

#include "mmh/common/collision_check.hpp"

#include <algorithm>
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
  const double t_end = traj.duration();
  if ((traj.position(0.0) - start.position).norm() > 1e-9 ||
      (traj.velocity(0.0) - start.velocity).norm() > 1e-9 ||
      (traj.acceleration(0.0) - start.acceleration).norm() > 1e-9)
    return fail("does not start at the requested state");
  const double end_err = (traj.position(t_end) - target).norm();
  if (end_err > params.endpoint_tolerance_m)
    return fail("ends " + fmt(end_err) + " m from the target");
  if (traj.velocity(t_end).norm() > 1e-3 || traj.acceleration(t_end).norm() > 1e-3)
    return fail("does not end at rest");

  r.max_speed = traj.maxSpeed();
  r.max_acceleration = traj.maxAcceleration();
  if (r.max_speed > max_vel_mps * (1.0 + params.limit_tolerance))
    return fail("max speed " + fmt(r.max_speed) + " m/s exceeds " + fmt(max_vel_mps));
  if (r.max_acceleration > max_acc_mps2 * (1.0 + params.limit_tolerance))
    return fail("max acceleration " + fmt(r.max_acceleration) + " m/s^2 exceeds " +
                fmt(max_acc_mps2));

  // Samples no more than a quarter voxel apart along the path.
  const double dt = std::max(1e-4, 0.25 * grid.resolution() / std::max(r.max_speed, 1e-3));
  // A start inside the inflated margin leaves it outwards: while the samples are in the margin,
  // none nearer to the occupied cells than escape_min_distance_m (mmh::keepsEscapeDistance).
  bool escaping = grid.isBlockedPoint(start.position);
  for (int i = 0; i < traj.numPieces(); ++i) {
    const Piece& piece = traj.pieces()[i];
    const int steps = std::max(1, static_cast<int>(std::ceil(piece.duration / dt)));
    const Polytope& own = corridor.polytopes.at(piece_polytope[i]);
    const PieceCoeffs& c = piece.coeffs;
    for (int j = 0; j <= steps; ++j) {
      // Horner on the piece's own coefficients (the same polynomial Piece::position evaluates).
      const double t = piece.duration * j / steps;
      Eigen::Vector3d p = c.col(kMaxPolyOrder - 1);
      for (int k = kMaxPolyOrder - 2; k >= 0; --k) p = p * t + c.col(k);
      ++r.samples;
      if (grid.isOccupiedPoint(p))
        return fail("sample at t-piece " + std::to_string(i) + " lies in an occupied voxel");
      if (escaping) {
        if (!grid.isBlockedPoint(p)) {
          escaping = false;
        } else if (!keepsEscapeDistance(grid, p, escape_min_distance_m)) {
          return fail("goes deeper into the inflated margin it starts in (piece " +
                      std::to_string(i) + ")");
        }
      }
      double v = own.maxViolation(p);
      if (v > params.corridor_tolerance_m) {
        for (const Polytope& other : corridor.polytopes) v = std::min(v, other.maxViolation(p));
      }
      r.max_corridor_violation_m = std::max(r.max_corridor_violation_m, v);
      if (v > params.corridor_tolerance_m)
        return fail("leaves the corridor by " + fmt(v) + " m in piece " + std::to_string(i));
    }
  }
  r.ok = true;
  return r;
}

}  // namespace mmh::som
