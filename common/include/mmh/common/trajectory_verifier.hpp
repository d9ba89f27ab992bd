// The one independent check of a trajectory, shared by the modes (FPM, SOM, EAM) and the
// arbiter's answer check: finite pieces; start state; end at the target at rest (optional);
// exact limits (trajectory_limits.hpp) with a relative and an absolute tolerance; geofence with
// a tolerance; collision against the occupied and (optionally) the inflated layer, where a start
// inside the inflated margin may leave it outwards only (never nearer to the occupied cells than
// escape_min_distance_m, mmh::keepsEscapeDistance) and, where set, within escape_radius_m.
//
// Every tolerance is the caller's (a different tolerance is a different flight), and so is the
// sampling: kPerPiece (SOM, EAM: each piece sampled so that samples lie at most a quarter voxel
// apart at the exact maximum speed, all checks per sample in that order) or kTimeSteps (the
// arbiter: the geofence every time_step_s, the escape walk every escape_step_s, then the
// collision check of firstCollisionTime).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <string>

#include "mmh/common/collision_check.hpp"
#include "mmh/common/trajectory.hpp"
#include "mmh/common/trajectory_limits.hpp"
#include "mmh/common/voxel_grid.hpp"

namespace mmh {

// The check that failed first.
enum class VerifyCheck {
  kNone,
  kNotFinite,     // empty, or a coefficient or duration not finite / not positive
  kStartState,    // does not start at the requested state
  kEndPosition,   // does not end at the target
  kEndNotAtRest,  // does not end at rest
  kSpeed,         // exact max speed above the limit (with tolerance)
  kAcceleration,  // exact max acceleration above the limit (with tolerance)
  kGeofence,      // a sample outside the geofence (with tolerance)
  kOccupied,      // a sample in an occupied cell
  kInflated,      // a sample in the inflated margin (outside the escape from the start)
  kEscapeDeeper,  // the escape from a start in the margin comes nearer to the occupied cells
  kEscapeTooFar,  // the escape leaves the margin further than escape_radius_m from the start
  kSample,        // the caller's own per-sample check (e.g. SOM's corridor)
};
const char* toString(VerifyCheck check);
inline bool isCollision(VerifyCheck c) {
  return c == VerifyCheck::kOccupied || c == VerifyCheck::kInflated ||
         c == VerifyCheck::kEscapeDeeper || c == VerifyCheck::kEscapeTooFar;
}

struct VerifierOptions {
  // --- start state (off when check_start is false) ---
  bool check_start = false;
  KinematicState start;
  double start_position_tol_m = 1e-9, start_velocity_tol_mps = 1e-9,
         start_acceleration_tol_mps2 = 1e-9;
  // --- end state (off when check_end is false): at target within end_position_tol_m, at rest ---
  bool check_end = false;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  double end_position_tol_m = 1e-6, rest_velocity_tol_mps = 1e-6, rest_acceleration_tol_mps2 = 1e-6;
  // --- limits: max <= limit * (1 + relative) + absolute (off when check_limits is false) ---
  bool check_limits = false;
  double max_vel_mps = 0.0, max_acc_mps2 = 0.0;
  double limit_relative_tol = 0.0, limit_absolute_tol = 0.0;
  MaximaMethod maxima = MaximaMethod::kStationaryPoints;
  bool limits_after_samples = false;  // EAM: a collision is reported before a broken limit
  // --- geofence: lo - tol <= p <= hi + tol (off when check_geofence is false) ---
  bool check_geofence = false;
  Eigen::Vector3d geofence_min = Eigen::Vector3d::Zero(), geofence_max = Eigen::Vector3d::Zero();
  double geofence_tol_m = 0.0;
  // --- collision (off when grid is null) ---
  const VoxelGrid* grid = nullptr;
  bool check_inflated = true;  // false: only the occupied layer (SOM: its corridor does the rest)
  // Escape from a start inside the inflated margin: no sample of it nearer to the occupied cells
  // than escape_min_distance_m (less escape_depth_tol_m) and, kPerPiece, none further than
  // escape_radius_m from the start position; kTimeSteps, every sample in the margin within
  // escape_radius_m of the start keeps that distance (escapeZoneEnd), and the first beyond it
  // is out of the margin.
  double escape_min_distance_m = 0.0;
  double escape_depth_tol_m = kEscapeDepthTolerance;
  double escape_radius_m = std::numeric_limits<double>::infinity();
  // kPerPiece: the escape lasts from the first sample while samples are blocked (true), or only
  // when the start position itself is blocked (false; SOM).
  bool escape_from_first_sample = true;
  // kPerPiece: samples up to this time after the start may lie in the inflated margin when they
  // keep escape_min_distance_m (mmh::forcedByStart).
  double forced_until_s = 0.0;
  // --- sampling ---
  enum class Sampling { kPerPiece, kTimeSteps };
  Sampling sampling = Sampling::kPerPiece;
  // kPerPiece: samples at most step_voxels * resolution apart at the exact max speed; time step
  // at least min_time_step_s. cubic_fast_path: pieces of degree <= 3 evaluated with their four
  // coefficients (EAM), otherwise Horner on all coefficients.
  double step_voxels = 0.25;
  double min_time_step_s = 1e-4;
  bool cubic_fast_path = false;
  // kTimeSteps: geofence samples every time_step_s, escape walk every escape_step_s.
  double time_step_s = 0.01, escape_step_s = 0.01;
  // kPerPiece: the caller's own check of each sample (piece index, trajectory time, point);
  // false (with *why) fails with kSample.
  std::function<bool(int piece, double t, const Eigen::Vector3d& p, std::string* why)> sample_check;
};

struct VerifyResult {
  bool ok = false;
  VerifyCheck failed = VerifyCheck::kNone;
  std::string why;                        // the first failed check in words, empty when ok
  double at_time = 0.0;                   // trajectory time of a failed sample
  int piece = -1;                         // piece of a failed sample (kPerPiece)
  double max_speed = 0.0, max_acc = 0.0;  // exact maxima (when the limits were computed)
  int samples = 0;                        // kPerPiece samples looked at
  bool collision() const { return isCollision(failed); }
};

VerifyResult verifyTrajectory(const Trajectory& traj, const VerifierOptions& options);

}  // namespace mmh
