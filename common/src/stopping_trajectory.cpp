#include "mmh/common/stopping_trajectory.hpp"

#include <algorithm>
#include <cmath>

#include "mmh/common/collision_check.hpp"
#include "mmh/common/minco.hpp"

namespace mmh {
namespace {

// A start may already accelerate harder than a_max (an emergency answer is accepted 5% over it):
// the stop may then keep that acceleration, never more, or no stop would ever fit.
double accelerationLimit(const KinematicState& start, double max_acc_mps2) {
  return std::max(max_acc_mps2, start.acceleration.norm()) * (1.0 + 1e-6);
}

// The re-timed curve is fitted with polynomial pieces, which may bulge this much above it.
constexpr double kSlowdownSpeedTolerance = 1.02;

// Longest stop worth trying: well past a bang-bang stop at half the deceleration. Beyond it a
// stop only drifts farther along (a stop of a minute once ran straight through the forest).
double longestStop(double speed, double max_acc_mps2) {
  return 4.0 * speed / max_acc_mps2 + 2.0;
}

}  // namespace

Trajectory makeStoppingTrajectory(const KinematicState& start, double max_acc_mps2,
                                  double max_vel_mps) {
  const double speed = start.velocity.norm();
  if (speed < 1e-3 && start.acceleration.norm() < 1e-3) {
    Piece hold;
    hold.duration = 1.0;
    hold.coeffs.col(0) = start.position;
    return Trajectory({hold});
  }
  // Three minimum-jerk pieces whose junctions follow a constant deceleration: close to the
  // bang-bang stop, with bounded jerk. Lengthen the stop until the exact maxima fit the limits.
  const Eigen::Vector3d dir =
      speed > 1e-6 ? Eigen::Vector3d(start.velocity / speed) : Eigen::Vector3d::Zero();
  const double speed_limit = std::max(max_vel_mps, speed);
  const double acc_limit = accelerationLimit(start, max_acc_mps2);
  // The shortest stop within the limits; if none fits, the one with the gentlest peak.
  Trajectory best;
  double best_peak = INFINITY;
  for (double total = std::max(0.2, 1.05 * speed / max_acc_mps2);
       total <= longestStop(speed, max_acc_mps2); total *= 1.08) {
    const double decel = speed / total;
    MincoJerk minco;
    Eigen::Matrix3d head, tail;
    head << start.position, start.velocity, start.acceleration;
    const double stop_dist = 0.5 * speed * total;
    tail << start.position + dir * stop_dist, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero();
    const int pieces = 3;
    minco.setConditions(head, tail, pieces);
    Eigen::Matrix3Xd inner(3, pieces - 1);
    for (int i = 1; i < pieces; ++i) {
      const double t = total * i / pieces;
      inner.col(i - 1) = start.position + dir * (speed * t - 0.5 * decel * t * t);
    }
    minco.setParameters(inner, Eigen::VectorXd::Constant(pieces, total / pieces));
    Trajectory stop = minco.trajectory();
    const double peak = stop.maxAcceleration();
    if (peak <= acc_limit && stop.maxSpeed() <= speed_limit * 1.0001) return stop;
    if (peak < best_peak) {
      best = std::move(stop);
      best_peak = peak;
    }
  }
  return best;
}

Trajectory makeStoppingTrajectory(const Trajectory& path, double t0, double max_acc_mps2,
                                  double max_vel_mps) {
  const KinematicState start = path.state(t0);
  const double speed = start.velocity.norm();
  const double remaining = path.duration() - t0;
  if (speed < 1e-3 || remaining <= 1e-3)
    return makeStoppingTrajectory(start, max_acc_mps2, max_vel_mps);
  const double speed_limit = std::max(max_vel_mps, speed);
  const double acc_limit = accelerationLimit(start, max_acc_mps2);
  // Time warp tau(t) with tau' = 1 - 3 u^2 + 2 u^3 (u = t / T): tau'' = 0 at both ends, so the
  // acceleration is continuous at the start and zero at rest; the curve is followed up to
  // tau(T) = T / 2. Peak path deceleration is 1.5 speed / T.
  for (double total = std::max(0.3, 1.5 * speed / (0.9 * max_acc_mps2));; total *= 1.1) {
    if (0.5 * total > remaining || total > 1.5 * longestStop(speed, max_acc_mps2)) {
      // Not enough path left to brake on: the straight stop from the same state.
      return makeStoppingTrajectory(start, max_acc_mps2, max_vel_mps);
    }
    auto warp = [&](double t) {
      const double u = t / total;
      return t0 + total * (u - u * u * u + 0.5 * u * u * u * u);
    };
    const int pieces = std::max(3, static_cast<int>(std::ceil(total / 0.15)));
    MincoJerk minco;
    Eigen::Matrix3d head, tail;
    head << start.position, start.velocity, start.acceleration;
    tail << path.position(warp(total)), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero();
    minco.setConditions(head, tail, pieces);
    Eigen::Matrix3Xd inner(3, pieces - 1);
    for (int i = 1; i < pieces; ++i) inner.col(i - 1) = path.position(warp(total * i / pieces));
    minco.setParameters(inner, Eigen::VectorXd::Constant(pieces, total / pieces));
    Trajectory stop = minco.trajectory();
    if (stop.maxAcceleration() <= acc_limit && stop.maxSpeed() <= speed_limit * 1.0001) return stop;
  }
}

Trajectory makeSlowdownTrajectory(const Trajectory& path, double t0, double max_speed_mps,
                                  double max_acc_mps2, double tolerance) {
  const double end = path.duration();
  if (t0 >= end - 1e-3 || max_speed_mps <= 0.0) return Trajectory();
  const double top_speed = path.tail(t0).maxSpeed();
  if (top_speed <= max_speed_mps * (1.0 + tolerance)) return Trajectory();
  const KinematicState start = path.state(t0);
  const double speed = start.velocity.norm();
  const double ratio = max_speed_mps / top_speed;
  const double acc_limit = accelerationLimit(start, max_acc_mps2);
  // Time warp with tau' = 1 - (1 - ratio)(3u^2 - 2u^3) over the transition (u = t / T), then
  // tau' = ratio: tau'' is zero at both ends of the transition, so the acceleration stays
  // continuous. Peak deceleration of the warp: 1.5 (1 - ratio) speed / T.
  for (double transition = std::max(0.3, 1.5 * (1.0 - ratio) * speed / (0.9 * max_acc_mps2));
       transition <= longestStop(speed, max_acc_mps2); transition *= 1.1) {
    const double warped_transition = t0 + 0.5 * transition * (1.0 + ratio);
    if (warped_transition >= end) break;
    const double total = transition + (end - warped_transition) / ratio;
    auto warp = [&](double t) {
      if (t >= transition) return std::min(end, warped_transition + ratio * (t - transition));
      const double u = t / transition;
      return t0 + t - (1.0 - ratio) * transition * (u * u * u - 0.5 * u * u * u * u);
    };
    const int pieces = std::max(3, static_cast<int>(std::ceil(total / 0.15)));
    MincoJerk minco;
    Eigen::Matrix3d head, tail;
    head << start.position, start.velocity, start.acceleration;
    tail << path.position(end), ratio * path.velocity(end), ratio * ratio * path.acceleration(end);
    minco.setConditions(head, tail, pieces);
    Eigen::Matrix3Xd inner(3, pieces - 1);
    for (int i = 1; i < pieces; ++i) inner.col(i - 1) = path.position(warp(total * i / pieces));
    minco.setParameters(inner, Eigen::VectorXd::Constant(pieces, total / pieces));
    Trajectory slow = minco.trajectory();
    bool slow_enough = slow.maxSpeed() <= top_speed * 1.0001;
    for (double t = transition; slow_enough && t < slow.duration(); t += 0.02)
      slow_enough = slow.velocity(t).norm() <= max_speed_mps * kSlowdownSpeedTolerance;
    if (slow_enough && slow.maxAcceleration() <= acc_limit) return slow;
  }
  return Trajectory();
}

namespace {

// Sample step along a trajectory: at most 1 cm apart in space.
double sampleStep(const Trajectory& traj) {
  return std::max(1e-3, 0.01 / std::max(1e-3, traj.maxSpeed()));
}

// Less unknown than this counts as none: sampling and the cell edges blur a few centimetres.
constexpr double kUnknownTolerance_m = 0.1;

}  // namespace

StopAssessment assessStop(const VoxelGrid& grid, const Trajectory& stop, double limit_m) {
  StopAssessment a;
  a.clearance_m = limit_m;
  if (stop.empty()) return a;
  // One walk for both: clearance at every sample, unknown length between samples.
  const double dt = sampleStep(stop);
  Eigen::Vector3d previous = stop.position(0.0);
  for (double t = 0.0;; t += dt) {
    const double tc = std::min(t, stop.duration());
    const Eigen::Vector3d p = stop.position(tc);
    a.clearance_m = std::min(a.clearance_m, occupiedDistance(grid, p, a.clearance_m));
    if (grid.atPoint(p) == Occupancy::kUnknown) a.unknown_m += (p - previous).norm();
    previous = p;
    if (tc >= stop.duration()) break;
  }
  return a;
}

double minOccupiedDistance(const VoxelGrid& grid, const Trajectory& traj, double limit_m) {
  return assessStop(grid, traj, limit_m).clearance_m;
}

bool saferStop(const StopAssessment& a, const StopAssessment& b, double touch_m) {
  const bool a_touches = a.clearance_m < touch_m;
  const bool b_touches = b.clearance_m < touch_m;
  if (a_touches != b_touches) return !a_touches;
  if (!a_touches && std::abs(a.unknown_m - b.unknown_m) > kUnknownTolerance_m)
    return a.unknown_m < b.unknown_m;
  return a.clearance_m > b.clearance_m;
}

Trajectory chooseStoppingTrajectory(const VoxelGrid* grid, const Trajectory& path, double t0,
                                    double max_acc_mps2, double max_vel_mps, double clearance_m,
                                    double touch_m) {
  Trajectory along = makeStoppingTrajectory(path, t0, max_acc_mps2, max_vel_mps);
  if (!grid || !grid->valid()) return along;
  const double limit = clearance_m + 0.1;
  const StopAssessment along_seen = assessStop(*grid, along, limit);
  if (along_seen.clearance_m >= clearance_m && along_seen.unknown_m <= kUnknownTolerance_m)
    return along;
  Trajectory straight = makeStoppingTrajectory(path.state(t0), max_acc_mps2, max_vel_mps);
  return saferStop(assessStop(*grid, straight, limit), along_seen, touch_m) ? straight : along;
}

}  // namespace mmh
