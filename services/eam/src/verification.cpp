#include "mmh/eam/verification.hpp"

#include "mmh/common/collision_check.hpp"
#include "mmh/common/trajectory_limits.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <sstream>

namespace mmh::eam {
namespace {

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

}  // namespace

Verification verifyTrajectory(const Trajectory& traj, const VoxelGrid& grid,
                              const KinematicState& start, const Eigen::Vector3d& target,
                              const EamParams& params) {
  Verification r;
  if (traj.empty() || !traj.isFinite()) {
    r.why = "trajectory is empty or not finite";
    return r;
  }
  constexpr double kStateTol = 1e-6;
  const double T = traj.duration();
  if ((traj.position(0.0) - start.position).norm() > kStateTol ||
      (traj.velocity(0.0) - start.velocity).norm() > kStateTol ||
      (traj.acceleration(0.0) - start.acceleration).norm() > kStateTol) {
    r.why = "does not start at the start state";
    return r;
  }
  if ((traj.position(T) - target).norm() > kStateTol || traj.velocity(T).norm() > kStateTol ||
      traj.acceleration(T).norm() > kStateTol) {
    r.why = "does not end at the target at rest";
    return r;
  }
  // Exact maxima: closed form for EAM's cubic pieces (trajectory_limits.hpp).
  const KinematicMaxima maxima = trajectoryMaxima(traj, MaximaMethod::kCubicClosedForm);
  r.max_speed = maxima.max_speed;
  r.max_acc = maxima.max_acc;

  // Dense samples, piece by piece, no two further apart than a quarter voxel.
  const double step_m = 0.25 * grid.resolution();
  const double dt = std::max(1e-5, step_m / std::max(1e-3, r.max_speed));
  const Eigen::Vector3d box_lo = params.geofence_min.array() - 0.01;
  const Eigen::Vector3d box_hi = params.geofence_max.array() + 0.01;
  bool escaping = true;
  const double escape_min_distance =
      escapeMinDistance(grid, start.position, params.start_escape_clearance_m);
  double t0 = 0.0;
  for (const Piece& piece : traj.pieces()) {
    // Pieces of degree <= 3 (EAM's) are evaluated with their four coefficients only.
    const bool cubic = piece.coeffs.rightCols(kMaxPolyOrder - 4).isZero(0.0);
    const Eigen::Vector3d c0 = piece.coeffs.col(0), c1 = piece.coeffs.col(1),
                          c2 = piece.coeffs.col(2), c3 = piece.coeffs.col(3);
    const int n = std::max(1, static_cast<int>(std::ceil(piece.duration / dt)));
    for (int k = 0; k <= n; ++k) {
      const double tl = piece.duration * k / n;
      const Eigen::Vector3d p =
          cubic ? Eigen::Vector3d(c0 + tl * (c1 + tl * (c2 + tl * c3))) : piece.position(tl);
      const Eigen::Vector3i cell = grid.localIndexOf(p);
      const bool in_window = grid.inWindow(cell);  // outside: unknown, i.e. free
      const int64_t idx = in_window ? grid.linearIndex(cell) : 0;
      if (in_window && grid.atLinear(idx) == Occupancy::kOccupied) {
        r.why = "hits an occupied cell at t=" + fmt(t0 + tl) + " s";
        r.collision = true;
        return r;
      }
      if (in_window && grid.isBlockedLinear(idx)) {
        if (!(escaping && (p - start.position).norm() <= params.start_escape_radius_m)) {
          r.why = "enters the inflated obstacles at t=" + fmt(t0 + tl) + " s";
          r.collision = true;
          return r;
        }
        if (!keepsEscapeDistance(grid, p, escape_min_distance)) {
          r.why = "goes deeper into the inflated margin it starts in at t=" + fmt(t0 + tl) + " s";
          r.collision = true;
          return r;
        }
      } else {
        escaping = false;
      }
      if ((p.array() < box_lo.array()).any() || (p.array() > box_hi.array()).any()) {
        r.why = "leaves the geofence at t=" + fmt(t0 + tl) + " s";
        return r;
      }
    }
    t0 += piece.duration;
  }
  const double tol = 1.0 + params.limit_tolerance_ratio;
  if (r.max_speed > tol * params.max_vel_mps) {
    r.why = "max speed " + fmt(r.max_speed) + " m/s exceeds the limit by more than the tolerance";
    return r;
  }
  if (r.max_acc > tol * params.max_acc_mps2) {
    r.why = "max acceleration " + fmt(r.max_acc) +
            " m/s^2 exceeds the limit by more than the tolerance";
    return r;
  }
  r.ok = true;
  return r;
}

}  // namespace mmh::eam
