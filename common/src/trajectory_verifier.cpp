#include "mmh/common/trajectory_verifier.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mmh/common/collision_check.hpp"

namespace mmh {
namespace {

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

VerifyResult& fail(VerifyResult& r, VerifyCheck check, std::string why) {
  r.ok = false;
  r.failed = check;
  r.why = std::move(why);
  return r;
}

VerifyResult& failAt(VerifyResult& r, VerifyCheck check, const std::string& what, int piece,
                     double t) {
  r.piece = piece;
  r.at_time = t;
  return fail(r, check, what + " at t=" + fmt(t) + " s");
}

bool checkStart(const Trajectory& traj, const VerifierOptions& o, VerifyResult& r) {
  if ((traj.position(0.0) - o.start.position).norm() > o.start_position_tol_m ||
      (traj.velocity(0.0) - o.start.velocity).norm() > o.start_velocity_tol_mps ||
      (traj.acceleration(0.0) - o.start.acceleration).norm() > o.start_acceleration_tol_mps2) {
    fail(r, VerifyCheck::kStartState, "does not start at the requested state");
    return false;
  }
  return true;
}

bool checkEnd(const Trajectory& traj, const VerifierOptions& o, VerifyResult& r) {
  const double t_end = traj.duration();
  const double end_err = (traj.position(t_end) - o.target).norm();
  if (end_err > o.end_position_tol_m) {
    fail(r, VerifyCheck::kEndPosition, "ends " + fmt(end_err) + " m from the target");
    return false;
  }
  if (traj.velocity(t_end).norm() > o.rest_velocity_tol_mps ||
      traj.acceleration(t_end).norm() > o.rest_acceleration_tol_mps2) {
    fail(r, VerifyCheck::kEndNotAtRest, "does not end at rest");
    return false;
  }
  return true;
}

void computeMaxima(const Trajectory& traj, const VerifierOptions& o, VerifyResult& r) {
  const KinematicMaxima m = trajectoryMaxima(traj, o.maxima);
  r.max_speed = m.max_speed;
  r.max_acc = m.max_acc;
}

bool checkLimits(const VerifierOptions& o, VerifyResult& r) {
  if (r.max_speed > o.max_vel_mps * (1.0 + o.limit_relative_tol) + o.limit_absolute_tol) {
    fail(r, VerifyCheck::kSpeed,
         "max speed " + fmt(r.max_speed) + " m/s exceeds " + fmt(o.max_vel_mps));
    return false;
  }
  if (r.max_acc > o.max_acc_mps2 * (1.0 + o.limit_relative_tol) + o.limit_absolute_tol) {
    fail(r, VerifyCheck::kAcceleration,
         "max acceleration " + fmt(r.max_acc) + " m/s^2 exceeds " + fmt(o.max_acc_mps2));
    return false;
  }
  return true;
}

bool outsideBox(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  return (p.array() < lo.array()).any() || (p.array() > hi.array()).any();
}

// Samples of every piece, at most step_voxels * resolution apart at the exact max speed; per
// sample: occupied, inflated margin / escape, geofence, the caller's check.
bool checkPerPiece(const Trajectory& traj, const VerifierOptions& o, VerifyResult& r) {
  const VoxelGrid* grid = o.grid;
  const double res = grid ? grid->resolution() : 0.0;
  const double dt = std::max(o.min_time_step_s, o.step_voxels * res / std::max(r.max_speed, 1e-3));
  const Eigen::Vector3d box_lo = o.geofence_min.array() - o.geofence_tol_m;
  const Eigen::Vector3d box_hi = o.geofence_max.array() + o.geofence_tol_m;
  bool escaping = grid && (o.escape_from_first_sample || grid->isBlockedPoint(o.start.position));
  double t0 = 0.0;
  for (int i = 0; i < traj.numPieces(); ++i) {
    const Piece& piece = traj.pieces()[i];
    const PieceCoeffs& c = piece.coeffs;
    const bool cubic = o.cubic_fast_path && isCubicPiece(piece);
    const int n = std::max(1, static_cast<int>(std::ceil(piece.duration / dt)));
    for (int k = 0; k <= n; ++k) {
      const double tl = piece.duration * k / n;
      Eigen::Vector3d p;
      if (cubic) {
        p = c.col(0) + tl * (c.col(1) + tl * (c.col(2) + tl * c.col(3)));
      } else {  // Horner on all coefficients (the polynomial Piece::position evaluates)
        p = c.col(kMaxPolyOrder - 1);
        for (int j = kMaxPolyOrder - 2; j >= 0; --j) p = p * tl + c.col(j);
      }
      ++r.samples;
      if (grid) {
        const Eigen::Vector3i cell = grid->localIndexOf(p);
        const bool in_window = grid->inWindow(cell);  // outside: unknown, i.e. free
        const int64_t idx = in_window ? grid->linearIndex(cell) : 0;
        if (in_window && grid->atLinear(idx) == Occupancy::kOccupied)
          return failAt(r, VerifyCheck::kOccupied, "hits an occupied cell", i, t0 + tl), false;
        if (escaping || o.check_inflated) {
          if (in_window && grid->isBlockedLinear(idx)) {
            if (!escaping) {
              if (!forcedByStart(*grid, p, t0 + tl, o.forced_until_s, o.escape_min_distance_m,
                                 o.escape_depth_tol_m))
                return failAt(r, VerifyCheck::kInflated, "enters the inflated obstacles", i,
                              t0 + tl),
                       false;
            } else if ((p - o.start.position).norm() > o.escape_radius_m) {
              return failAt(r, VerifyCheck::kEscapeTooFar,
                            "stays in the inflated margin it starts in too far from the start", i,
                            t0 + tl),
                     false;
            } else if (!keepsEscapeDistance(*grid, p, o.escape_min_distance_m,
                                            o.escape_depth_tol_m)) {
              return failAt(r, VerifyCheck::kEscapeDeeper,
                            "goes deeper into the inflated margin it starts in", i, t0 + tl),
                     false;
            }
          } else {
            escaping = false;
          }
        }
      }
      if (o.check_geofence && outsideBox(p, box_lo, box_hi))
        return failAt(r, VerifyCheck::kGeofence, "leaves the geofence", i, t0 + tl), false;
      std::string why;
      if (o.sample_check && !o.sample_check(i, t0 + tl, p, &why)) {
        r.piece = i;
        r.at_time = t0 + tl;
        return fail(r, VerifyCheck::kSample, why), false;
      }
    }
    t0 += piece.duration;
  }
  return true;
}

// The arbiter's sampling: the geofence on a time grid, then (with a map) the escape walk from a
// start in the margin and the collision check of firstCollisionTime from where it ends.
bool checkTimeSteps(const Trajectory& t, const VerifierOptions& o, VerifyResult& r) {
  if (o.check_geofence) {
    for (double time = 0.0; time <= t.duration(); time += o.time_step_s) {
      const Eigen::Vector3d p = t.position(time);
      if ((p.array() < o.geofence_min.array() - o.geofence_tol_m).any() ||
          (p.array() > o.geofence_max.array() + o.geofence_tol_m).any()) {
        r.at_time = time;
        return fail(r, VerifyCheck::kGeofence, "leaves the geofence"), false;
      }
    }
  }
  if (!o.grid) return true;
  const VoxelGrid& grid = *o.grid;
  const Eigen::Vector3d s0 = t.position(0.0);
  double clear_from = 0.0;
  if (isPointBlocked(grid, s0)) {
    // A start inside the margin may leave it: through no occupied voxel, outwards only, out of
    // the margin near the start.
    if (const auto hit =
            firstCollisionTime(grid, t, 0.0, t.duration(), CollisionLayer::kOccupied)) {
      r.at_time = *hit;
      return fail(r, VerifyCheck::kOccupied, "enters an obstacle"), false;
    }
    // Near the start it may touch the margin again (a cell's centre nearer than the margin
    // while the point itself is farther: the cells are coarser than the way out) as long as it
    // never comes nearer than the start.
    const double zone_end = escapeZoneEnd(t, o.escape_radius_m, o.escape_step_s);
    if (const auto deeper = firstEscapeTooDeep(grid, t, 0.0, zone_end, o.escape_step_s,
                                               o.escape_min_distance_m, o.escape_depth_tol_m)) {
      r.at_time = *deeper;
      return fail(r, VerifyCheck::kEscapeDeeper, "goes deeper into the margin it starts in"), false;
    }
    clear_from = zone_end;
    if (zone_end < t.duration() && isPointBlocked(grid, t.position(clear_from))) {
      r.at_time = clear_from;
      return fail(r, VerifyCheck::kEscapeTooFar, "does not leave the margin near its start"), false;
    }
  }
  if (const auto hit = firstCollisionTime(
          grid, t, clear_from, t.duration(),
          o.check_inflated ? CollisionLayer::kInflated : CollisionLayer::kOccupied)) {
    r.at_time = *hit;
    return fail(r, o.check_inflated ? VerifyCheck::kInflated : VerifyCheck::kOccupied,
                "collides with the map"),
           false;
  }
  return true;
}

}  // namespace

const char* toString(VerifyCheck check) {
  switch (check) {
    case VerifyCheck::kNone:
      return "none";
    case VerifyCheck::kNotFinite:
      return "not finite";
    case VerifyCheck::kStartState:
      return "start state";
    case VerifyCheck::kEndPosition:
      return "end position";
    case VerifyCheck::kEndNotAtRest:
      return "end not at rest";
    case VerifyCheck::kSpeed:
      return "speed";
    case VerifyCheck::kAcceleration:
      return "acceleration";
    case VerifyCheck::kGeofence:
      return "geofence";
    case VerifyCheck::kOccupied:
      return "occupied";
    case VerifyCheck::kInflated:
      return "inflated";
    case VerifyCheck::kEscapeDeeper:
      return "escape deeper";
    case VerifyCheck::kEscapeTooFar:
      return "escape too far";
    case VerifyCheck::kSample:
      return "sample";
  }
  return "?";
}

VerifyResult verifyTrajectory(const Trajectory& traj, const VerifierOptions& o) {
  VerifyResult r;
  if (traj.empty() || !traj.isFinite())
    return fail(r, VerifyCheck::kNotFinite, "trajectory is empty or not finite");
  if (o.check_start && !checkStart(traj, o, r)) return r;
  if (o.check_end && !checkEnd(traj, o, r)) return r;
  // The maxima set the sample spacing, so they are computed even when the limits come last.
  if (o.check_limits || (o.grid && o.sampling == VerifierOptions::Sampling::kPerPiece))
    computeMaxima(traj, o, r);
  if (o.check_limits && !o.limits_after_samples && !checkLimits(o, r)) return r;
  const bool samples_ok = o.sampling == VerifierOptions::Sampling::kPerPiece
                              ? checkPerPiece(traj, o, r)
                              : checkTimeSteps(traj, o, r);
  if (!samples_ok) return r;
  if (o.check_limits && o.limits_after_samples && !checkLimits(o, r)) return r;
  r.ok = true;
  return r;
}

}  // namespace mmh
