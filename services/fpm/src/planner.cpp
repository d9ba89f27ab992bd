#include "mmh/fpm/planner.hpp"
#include "mmh/common/vehicle_limits.hpp"

#include <algorithm>
#include <cmath>

#include "mmh/common/geofence.hpp"
#include "mmh/common/trajectory_limits.hpp"
#include "mmh/common/trajectory_verifier.hpp"
#include "mmh/fpm/initial_guess.hpp"

namespace mmh::fpm {
namespace {

// FPM checks its limits with the Bernstein bound (never below the true maximum).
KinematicMaxima measureLimits(const Trajectory& traj) {
  return trajectoryMaxima(traj, MaximaMethod::kBernsteinBound);
}

constexpr double kSamePointM = 1e-3;  // start and target closer than this are "the same"

bool finite(const Eigen::Vector3d& v) {
  return v.allFinite();
}

bool inside(const Eigen::Vector3d& p, const Params& params) {
  return insideBox(p, params.geofence_min_m, params.geofence_max_m);
}

}  // namespace

bool Planner::validate(const Request& r, Result& out) const {
  auto fail = [&](PlanStatus status, const std::string& detail) {
    out.ok = false;
    out.status = status;
    out.detail = detail;
    return false;
  };
  bool all_finite = finite(r.start.position) && finite(r.start.velocity) &&
                    finite(r.start.acceleration) && finite(r.target);
  for (const Eigen::Vector3d& w : r.waypoints) all_finite = all_finite && finite(w);
  if (!all_finite) return fail(PlanStatus::kBadInput, "request has NaN or Inf values");
  if (!inside(r.target, params_))
    return fail(PlanStatus::kTargetOutOfBounds, "target is outside the geofence");
  for (const Eigen::Vector3d& w : r.waypoints)
    if (!inside(w, params_))
      return fail(PlanStatus::kTargetOutOfBounds, "a waypoint is outside the geofence");
  const double v0 = r.start.velocity.norm(), a0 = r.start.acceleration.norm();
  const double vmax = params_.max_vel_mps, amax = params_.max_acc_mps2;
  if (v0 > vmax * (1.0 + 1e-9) || a0 > amax * (1.0 + 1e-9))
    return fail(PlanStatus::kInfeasibleStart, "start speed " + std::to_string(v0) +
                                                  " m/s or acceleration " + std::to_string(a0) +
                                                  " m/s^2 is above the limits");
  // At the speed limit and still speeding up: the limit breaks at once, whatever follows.
  if (v0 > vmax * (1.0 - 1e-9) && r.start.velocity.dot(r.start.acceleration) > 1e-9)
    return fail(PlanStatus::kInfeasibleStart, "start is at the speed limit and still accelerating");
  Eigen::Vector3d prev = r.start.position;
  for (const Eigen::Vector3d& w : r.waypoints) {
    if ((w - prev).norm() < kSamePointM)
      return fail(PlanStatus::kBadInput, "two consecutive waypoints coincide");
    prev = w;
  }
  if ((r.target - prev).norm() < kSamePointM) {
    if (r.waypoints.empty() && v0 < 1e-6 && a0 < 1e-6)
      return fail(PlanStatus::kStartEqualsTarget,
                  "start equals target and is at rest: nothing to plan (hold position)");
    if (!r.waypoints.empty())
      return fail(PlanStatus::kBadInput, "the last waypoint equals the target");
    // Moving through the target: plan the way back to it (the profile turns around).
  }
  return true;
}

Result Planner::plan(const Request& request) const {
  const double speed_limit = speedLimitFor(request.max_speed_mps, params_.max_vel_mps);
  if (speed_limit < params_.max_vel_mps) {
    Params slower = params_;
    slower.max_vel_mps = speed_limit;
    Request at_limit = request;
    at_limit.max_speed_mps = 0.0;
    return Planner(slower).plan(at_limit);
  }
  Result out;
  if (!validate(request, out)) return out;
  // A guess that is not exactly inside the limits (sideways starts, corners) or a result that
  // oversteps them between penalty samples is retried with wider margins: the whole plan is
  // made again, more conservatively.
  double margin = params_.limit_margin_ratio;
  for (int attempt = 0; attempt < 3; ++attempt, margin = std::min(0.2, 4.0 * margin + 0.01)) {
    if (attempt > 0) ++out.repairs;
    if (planWithMargin(request, margin, out)) return out;
  }
  out.ok = false;
  out.trajectory = Trajectory();
  out.status = PlanStatus::kVerify;
  out.detail = "limits still broken with the widest margin: max speed " +
               std::to_string(out.max_speed) + " m/s, max acceleration " +
               std::to_string(out.max_acc) + " m/s^2";
  return out;
}

bool Planner::planWithMargin(const Request& request, double margin_ratio, Result& out) const {
  const double vmax = params_.max_vel_mps, amax = params_.max_acc_mps2;
  const double margin = 1.0 - margin_ratio;

  GuessOptions guess_options;
  guess_options.v_max = vmax * margin;
  guess_options.a_max = amax * margin;
  // Ramp of the initial S-curves: the jerk energy of the four ramps of a rest-to-rest flight,
  // 4 a^2 / ramp, against the time they add, rho ramp, is smallest at ramp = 2 a / sqrt(rho).
  guess_options.ramp_s = std::clamp(2.0 * amax / std::sqrt(params_.time_weight), 0.05, 1.0);
  const InitialGuess guess =
      makeInitialGuess(request.start, request.target, request.waypoints, guess_options);
  out.profile_duration = guess.profile_duration;

  SpatioTemporalOptimizer optimizer;
  optimizer.setup(guess.knots, guess.fixed, guess.durations);
  // Without waypoints the optimum lies in the line or plane through the start spanned by the
  // direction to the target and the start velocity and acceleration (a symmetry of the problem):
  // optimise only there.
  const Eigen::Vector3d to_target = request.target - request.start.position;
  bool on_line = false;
  if (request.waypoints.empty() && to_target.norm() > kSamePointM) {
    Eigen::Matrix3Xd basis = to_target.normalized();
    for (const Eigen::Vector3d& v : {request.start.velocity, request.start.acceleration}) {
      const Eigen::Vector3d across = v - basis * (basis.transpose() * v);
      if (across.norm() > 1e-9 * std::max(1.0, v.norm()) && basis.cols() < 3) {
        basis.conservativeResize(3, basis.cols() + 1);
        basis.col(basis.cols() - 1) = across.normalized();
      }
    }
    if (basis.cols() < 3) optimizer.restrictTo(request.start.position, basis);
    on_line = basis.cols() == 1;
  }
  const Trajectory initial = optimizer.trajectory();

  OptimizerSettings settings;
  // A start at full speed cannot keep the margin: let the penalties start at the start speed.
  const double v_limit = std::max(vmax * margin, std::min(vmax, request.start.velocity.norm()));
  settings.v_limit = v_limit;
  settings.a_limit = amax * margin;
  settings.time_weight = params_.time_weight;
  settings.penalty_weight = params_.penalty_weight;
  settings.samples_per_piece = params_.samples_per_piece;
  // Corners at waypoints are far from the straight-line guess: give them a larger budget.
  settings.max_evaluations = params_.max_evaluations * (request.waypoints.empty() ? 1 : 5);
  out.evaluations += optimizer.optimize(settings);

  // Exact check of the limits over the whole trajectory (Bernstein bounds,
  // mmh/common/trajectory_limits.hpp). The penalties only see samples; if the result breaks a limit
  // between them, re-optimise once with the penalty limits lowered by the overshoot and denser
  // samples. Of the candidates that pass - including the initial guess, an S-curve inside the
  // limits by construction when the start moves along the path - the one with the lowest cost wins.
  Trajectory traj = optimizer.trajectory();
  KinematicMaxima limits = measureLimits(traj);
  // On a line the guess is already within ~0.1 % of the optimum: take it rather than
  // re-optimising.
  if (!limits.within(vmax, amax) && on_line) {
    const KinematicMaxima initial_limits = measureLimits(initial);
    if (initial_limits.within(vmax, amax)) {
      ++out.repairs;
      optimizer.setup(guess.knots, guess.fixed, guess.durations);
      traj = initial;
      limits = initial_limits;
    }
  }
  if (!limits.within(vmax, amax)) {
    ++out.repairs;
    settings.v_limit *= std::min(1.0, vmax / limits.max_speed) * (1.0 - 0.002);
    settings.a_limit *= std::min(1.0, amax / limits.max_acc) * (1.0 - 0.002);
    settings.samples_per_piece *= 2;
    out.evaluations += optimizer.optimize(settings);
    traj = optimizer.trajectory();
    limits = measureLimits(traj);
    const KinematicMaxima initial_limits = measureLimits(initial);
    const auto cost = [&](const Trajectory& t) {
      return t.jerkEnergy() + params_.time_weight * t.duration();
    };
    if (initial_limits.within(vmax, amax) &&
        (!limits.within(vmax, amax) || cost(initial) < cost(traj))) {
      optimizer.setup(guess.knots, guess.fixed, guess.durations);
      traj = initial;
      limits = initial_limits;
    }
  }
  out.max_speed = limits.max_speed;
  out.max_acc = limits.max_acc;
  // Accepted by the shared verifier: finite pieces, exact limits (Bernstein bound) within 1e-9.
  VerifierOptions check;
  check.check_limits = true;
  check.max_vel_mps = vmax;
  check.max_acc_mps2 = amax;
  check.limit_absolute_tol = 1e-9;
  check.maxima = MaximaMethod::kBernsteinBound;
  if (!verifyTrajectory(traj, check).ok) return false;
  out.ok = true;
  out.status = PlanStatus::kOk;
  out.detail.clear();
  out.trajectory = std::move(traj);
  settings.v_limit = v_limit;
  settings.a_limit = amax * margin;
  out.cost = optimizer.costs(settings);
  return true;
}

}  // namespace mmh::fpm
