#include "mmh/common/stopping_trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

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

// How long each minimum-jerk piece fitted to a re-timed curve lasts.
constexpr double kFitPieceS = 0.15;

// A re-timed curve as a trajectory: minimum-jerk pieces of about kFitPieceS through
// path.position(warp(t)) over [0, total], from exactly `start` to the `tail` state (position,
// velocity, acceleration as columns).
template <typename Warp>
Trajectory fitRetimed(const Trajectory& path, const KinematicState& start,
                      const Eigen::Matrix3d& tail, double total, const Warp& warp) {
  const int pieces = std::max(3, static_cast<int>(std::ceil(total / kFitPieceS)));
  MincoJerk minco;
  Eigen::Matrix3d head;
  head << start.position, start.velocity, start.acceleration;
  minco.setConditions(head, tail, pieces);
  Eigen::Matrix3Xd inner(3, pieces - 1);
  for (int i = 1; i < pieces; ++i) inner.col(i - 1) = path.position(warp(total * i / pieces));
  minco.setParameters(inner, Eigen::VectorXd::Constant(pieces, total / pieces));
  return minco.trajectory();
}

// How long braking first takes to build up and to fade: short enough to stop nearly as a bang-bang
// stop would, long enough for the minimum-jerk pieces (kFitPieceS) to follow.
constexpr double kFirstBrakeRampS = 0.2;
constexpr double kWarpStepS = 0.002;

// Below this speed braking is all build-up and fade: the three-piece stop.
constexpr double kNearlyAtRestMps = 0.05;

// Time warp of a stop along a path: path time tau at equal steps of stop time, from tau = t0
// (at the path's own pace) to rest. The warp rate sigma = dtau/dt falls as fast as the
// acceleration budget allows: the vehicle's acceleration p''(tau) sigma^2 + p'(tau) sigma' stays
// within acc_budget, so a bend's centripetal part is paid for first and braking takes the rest.
// sigma' ramps in and out over ramp_s, so the acceleration is continuous at the start and zero
// at rest. Where the path alone is over the budget (a bend flown at a_max) braking follows the
// ramp: slowing down lowers the bend's part as fast as braking adds its own. Empty when the path
// ends before the vehicle would be at rest.
std::vector<double> brakingWarp(const Trajectory& path, double t0, double acc_budget, double ramp_s,
                                double longest_s) {
  const double speed = path.velocity(t0).norm();
  const double jerk = acc_budget / std::max(speed, 1e-3) / ramp_s;  // in sigma''
  std::vector<double> taus{t0};
  double tau = t0, sigma = 1.0, rate = 0.0;  // rate = sigma'
  while (sigma > 1e-6) {
    if (taus.size() * kWarpStepS > longest_s) return {};
    const Eigen::Vector3d b = path.velocity(tau);
    const Eigen::Vector3d c = path.acceleration(tau) * sigma * sigma;
    // Most negative sigma' with |c + b sigma'| <= acc_budget (or the least violation).
    const double qa = b.squaredNorm();
    const double qb = 2.0 * b.dot(c);
    const double disc = qb * qb - 4.0 * qa * (c.squaredNorm() - acc_budget * acc_budget);
    double lowest, highest;
    if (qa < 1e-12) {
      lowest = highest = -INFINITY;
    } else if (disc < 0.0) {
      lowest = -INFINITY;
      highest = 0.0;
    } else {
      lowest = (-qb - std::sqrt(disc)) / (2.0 * qa);
      highest = (-qb + std::sqrt(disc)) / (2.0 * qa);
    }
    // Braking builds up and fades at a bounded jerk; the budget may force it faster.
    const double ramped =
        std::max({lowest, rate - jerk * kWarpStepS, -std::sqrt(2.0 * jerk * sigma)});
    rate = std::min({ramped, highest, 0.0});
    if (!std::isfinite(rate)) rate = -sigma / kWarpStepS;
    const double next = std::max(0.0, sigma + rate * kWarpStepS);
    tau += 0.5 * (sigma + next) * kWarpStepS;
    sigma = next;
    if (tau >= path.duration()) return {};
    taus.push_back(tau);
  }
  return taus;
}

// Braking along `path` from its time t0 (brakingWarp), fitted with minimum-jerk pieces through
// points of the re-timed curve; nothing when the path ends first or no fit keeps the limits.
std::optional<Trajectory> brakeAlong(const Trajectory& path, double t0, double max_acc_mps2,
                                     double max_vel_mps) {
  const KinematicState start = path.state(t0);
  const double speed = start.velocity.norm();
  const double speed_limit = std::max(max_vel_mps, speed);
  const double acc_limit = accelerationLimit(start, max_acc_mps2);
  // The fit may bulge over the warp's acceleration, and a bend flown near a_max leaves little to
  // brake with: brake more gently and build up more slowly until it fits.
  double budget = 0.95 * acc_limit;
  for (double ramp_s = kFirstBrakeRampS; ramp_s < 2.5; ramp_s *= 1.25, budget *= 0.95) {
    const std::vector<double> taus =
        brakingWarp(path, t0, budget, ramp_s, 1.5 * longestStop(speed, max_acc_mps2));
    if (taus.empty()) return std::nullopt;
    const double total = (taus.size() - 1) * kWarpStepS;
    auto warp = [&](double t) {
      const double at = std::clamp(t / kWarpStepS, 0.0, static_cast<double>(taus.size() - 1));
      const size_t i = std::min(static_cast<size_t>(at), taus.size() - 2);
      return taus[i] + (at - i) * (taus[i + 1] - taus[i]);
    };
    Eigen::Matrix3d at_rest;
    at_rest << path.position(taus.back()), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero();
    const Trajectory stop = fitRetimed(path, start, at_rest, total, warp);
    if (stop.maxAcceleration() <= acc_limit && stop.maxSpeed() <= speed_limit * 1.0001) return stop;
  }
  return std::nullopt;
}

// The straight path ahead of a state: its acceleration fades out within kFirstBrakeRampS, then
// it runs on at the speed reached, far enough for any stop.
Trajectory fadingStraightPath(const KinematicState& start, double max_acc_mps2) {
  const double fade = kFirstBrakeRampS;
  Piece bend;
  bend.duration = fade;
  bend.coeffs.col(0) = start.position;
  bend.coeffs.col(1) = start.velocity;
  bend.coeffs.col(2) = 0.5 * start.acceleration;
  bend.coeffs.col(3) = -start.acceleration / (6.0 * fade);
  const KinematicState end = Trajectory({bend}).state(fade);
  Piece run;
  run.duration = 2.0 * longestStop(end.velocity.norm(), max_acc_mps2);
  run.coeffs.col(0) = end.position;
  run.coeffs.col(1) = end.velocity;
  return Trajectory({bend, run});
}

// How far aside of the straight stop's end the stops that swerve end.
constexpr double kSwerveAsideM[] = {0.2, 0.4, 0.6, 0.8, 1.0};

// The straight stop from nearly at rest, or when braking along the faded path does not fit: three
// minimum-jerk pieces whose junctions follow a constant deceleration, lengthened until the exact
// maxima fit the limits. With `aside`, a stop that swerves: six pieces whose junctions also move
// smoothly (3u^2 - 2u^3) to that offset from the straight line, over the first aside_share of the
// stop's time.
Trajectory stopInPieces(const KinematicState& start, double max_acc_mps2, double max_vel_mps,
                        const Eigen::Vector3d& aside = Eigen::Vector3d::Zero(),
                        double aside_share = 1.0) {
  const double speed = start.velocity.norm();
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
    tail << start.position + dir * stop_dist + aside, Eigen::Vector3d::Zero(),
        Eigen::Vector3d::Zero();
    const int pieces = aside.isZero() ? 3 : 6;
    minco.setConditions(head, tail, pieces);
    Eigen::Matrix3Xd inner(3, pieces - 1);
    for (int i = 1; i < pieces; ++i) {
      const double t = total * i / pieces;
      const double u = std::min(1.0, static_cast<double>(i) / pieces / aside_share);
      inner.col(i - 1) = start.position + dir * (speed * t - 0.5 * decel * t * t) +
                         aside * (u * u * (3.0 - 2.0 * u));
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
  if (speed > kNearlyAtRestMps) {
    if (auto stop =
            brakeAlong(fadingStraightPath(start, max_acc_mps2), 0.0, max_acc_mps2, max_vel_mps))
      return *stop;
  }
  return stopInPieces(start, max_acc_mps2, max_vel_mps);
}

Trajectory makeStoppingTrajectory(const Trajectory& path, double t0, double max_acc_mps2,
                                  double max_vel_mps) {
  const KinematicState start = path.state(t0);
  if (start.velocity.norm() > kNearlyAtRestMps && path.duration() - t0 > 1e-3) {
    if (auto stop = brakeAlong(path, t0, max_acc_mps2, max_vel_mps)) return *stop;
  }
  // Not enough path left to brake on, or no fit: the straight stop from the same state.
  return makeStoppingTrajectory(start, max_acc_mps2, max_vel_mps);
}

Trajectory makeSlowdownTrajectory(const Trajectory& path, double t0, double max_speed_mps,
                                  double max_acc_mps2, double tolerance) {
  const double end = path.duration();
  if (t0 >= end - 1e-3 || max_speed_mps <= 0.0) return Trajectory();
  const double top_speed = path.tail(t0).maxSpeed();
  if (top_speed <= max_speed_mps * (1.0 + tolerance)) return Trajectory();
  // Re-timed to a small share of its speed the rest would take ages (and its fit as long):
  // braking to rest serves better.
  if (max_speed_mps < kMinSlowdownRatio * top_speed) return Trajectory();
  // Nor is a curve slowed again and again (every failed round slows the last slowdown) re-timed
  // past kLongestSlowdownS: its fit grows with its length, and so does every check of it.
  if ((end - t0) * top_speed / max_speed_mps > kLongestSlowdownS) return Trajectory();
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
    Eigen::Matrix3d slowed_end;
    slowed_end << path.position(end), ratio * path.velocity(end),
        ratio * ratio * path.acceleration(end);
    const Trajectory slow = fitRetimed(path, start, slowed_end, total, warp);
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

// How far a clearance search looks past the clearance found so far, so that the samples after it
// need no search of their own (assessStop).
constexpr double kClearanceSkip_m = 0.1;

// Less unknown than this counts as none: sampling and the cell edges blur a few centimetres.
constexpr double kUnknownTolerance_m = 0.1;

// A stop along a bend flown near a_max has little left to brake with and runs on; past this
// ratio of the straight stop's length the straight one is taken when it is as clear.
constexpr double kMuchLongerStop = 1.3;

// Clearance is measured this far past what a clear stop needs, so that the safer of two stops
// that are not clear can still be told apart.
constexpr double kClearanceSeenBeyond_m = 0.1;

// Every sample of the trajectory (1 cm apart at most) inside the fence.
bool staysInside(const Geofence& fence, const Trajectory& traj) {
  const double dt = sampleStep(traj);
  for (double t = 0.0; t < traj.duration() + dt; t += dt) {
    if (!insideGeofence(fence, traj.position(std::min(t, traj.duration())))) return false;
  }
  return true;
}

// Keeps clearance_m from the occupied cells' centres through known space (kUnknownTolerance_m).
bool isClear(const StopAssessment& seen, double clearance_m) {
  return seen.clearance_m >= clearance_m && seen.unknown_m <= kUnknownTolerance_m;
}

}  // namespace

StopAssessment assessStop(const VoxelGrid& grid, const Trajectory& stop, double limit_m) {
  StopAssessment a;
  a.clearance_m = limit_m;
  if (stop.empty()) return a;
  // One walk for both: clearance at every sample, unknown length between samples. The distance
  // to the occupied cells changes by at most the distance moved, so a sample nearer to the last
  // searched one than that search's distance minus the clearance so far cannot lower it and is
  // not searched: one search per kClearanceSkip_m in free space instead of one per centimetre.
  const double dt = sampleStep(stop);
  Eigen::Vector3d previous = stop.position(0.0);
  Eigen::Vector3d searched = previous;
  double searched_distance_m = -1.0;  // none yet
  for (double t = 0.0;; t += dt) {
    const double tc = std::min(t, stop.duration());
    const Eigen::Vector3d p = stop.position(tc);
    if (searched_distance_m - (p - searched).norm() < a.clearance_m) {
      searched = p;
      searched_distance_m = occupiedDistance(grid, p, a.clearance_m + kClearanceSkip_m);
      a.clearance_m = std::min(a.clearance_m, searched_distance_m);
    }
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

std::optional<Trajectory> firstSwervingStop(const KinematicState& start, double max_acc_mps2,
                                            double max_vel_mps,
                                            const std::function<bool(const Trajectory&)>& accept) {
  const double speed = start.velocity.norm();
  if (speed <= kNearlyAtRestMps) return std::nullopt;
  const Eigen::Vector3d ahead = start.velocity / speed;
  Eigen::Vector3d left(-ahead.y(), ahead.x(), 0.0);        // horizontal, square to the motion
  if (left.norm() < 0.1) left = Eigen::Vector3d::UnitY();  // flying nearly straight up or down
  left.normalize();
  const double speed_limit = std::max(max_vel_mps, speed);
  const double acc_limit = accelerationLimit(start, max_acc_mps2);
  for (double aside_m : kSwerveAsideM) {
    for (double sign : {1.0, -1.0}) {
      for (double share : {0.5, 0.75, 1.0}) {
        Trajectory stop =
            stopInPieces(start, max_acc_mps2, max_vel_mps, sign * aside_m * left, share);
        if (stop.maxAcceleration() <= acc_limit && stop.maxSpeed() <= speed_limit * 1.0001 &&
            accept(stop))
          return stop;
      }
    }
  }
  return std::nullopt;
}

std::vector<Trajectory> makeSwervingStops(const KinematicState& start, double max_acc_mps2,
                                          double max_vel_mps) {
  std::vector<Trajectory> stops;
  firstSwervingStop(start, max_acc_mps2, max_vel_mps, [&](const Trajectory& stop) {
    stops.push_back(stop);
    return false;
  });
  return stops;
}

namespace {

// One candidate stop and what the choice needs to know of it, each part computed once.
struct CandidateStop {
  Trajectory trajectory;
  StopAssessment seen;
  bool inside = true;  // within the geofence (or no fence)
  bool clear = false;  // inside, clear of the known obstacles through known space, and passes
                       // the arbiter's collision check
  bool meets_condition = true;  // the caller's further condition (also_clear)
};

CandidateStop examineStop(const VoxelGrid& grid, Trajectory stop, double clearance_m,
                          const Geofence* fence, const StopCondition& also_clear) {
  CandidateStop c;
  c.trajectory = std::move(stop);
  c.inside = !fence || staysInside(*fence, c.trajectory);
  c.seen = assessStop(grid, c.trajectory, clearance_m + kClearanceSeenBeyond_m);
  c.clear = c.inside && isClear(c.seen, clearance_m) &&
            !firstCollisionTime(grid, c.trajectory, 0.0, c.trajectory.duration());
  if (c.clear && also_clear) c.meets_condition = also_clear(c.trajectory);
  c.clear = c.clear && c.meets_condition;
  return c;
}

}  // namespace

bool isClearStop(const VoxelGrid& grid, const Trajectory& stop, double clearance_m,
                 const Geofence* fence, const StopCondition& also_clear) {
  // The cheap checks first: most candidate swerves fail them.
  if ((fence && !staysInside(*fence, stop)) || firstCollisionTime(grid, stop, 0.0, stop.duration()))
    return false;
  return examineStop(grid, stop, clearance_m, nullptr, also_clear).clear;
}

Trajectory chooseStoppingTrajectory(const VoxelGrid* grid, const Trajectory& path, double t0,
                                    double max_acc_mps2, double max_vel_mps, double clearance_m,
                                    double touch_m, bool may_swerve, const Geofence* fence,
                                    const StopCondition& also_clear) {
  Trajectory along_stop = makeStoppingTrajectory(path, t0, max_acc_mps2, max_vel_mps);
  if (!grid || !grid->valid()) return along_stop;
  Trajectory straight_stop = makeStoppingTrajectory(path.state(t0), max_acc_mps2, max_vel_mps);
  const bool along_much_longer =
      along_stop.arcLength() > kMuchLongerStop * straight_stop.arcLength();
  const CandidateStop along =
      examineStop(*grid, std::move(along_stop), clearance_m, fence, also_clear);
  if (along.clear && !along_much_longer) return along.trajectory;
  const CandidateStop straight =
      examineStop(*grid, std::move(straight_stop), clearance_m, fence, also_clear);
  if (along.clear) return straight.clear ? straight.trajectory : along.trajectory;
  // Braking along is refused by the caller's condition alone: the clear straight stop.
  if (straight.clear && !along.meets_condition) return straight.trajectory;
  // The swerves that are not clear, kept in case both braking stops would bring the airframe into
  // an occupied cell (assessed only then: a clear swerve is the usual answer).
  std::vector<Trajectory> unclear_swerves;
  if (may_swerve && !straight.clear) {
    if (auto swerve = firstSwervingStop(
            path.state(t0), max_acc_mps2, max_vel_mps, [&](const Trajectory& stop) {
              if (isClearStop(*grid, stop, clearance_m, fence, also_clear)) return true;
              unclear_swerves.push_back(stop);
              return false;
            }))
      return *swerve;
  }
  if (along.inside != straight.inside) {
    const CandidateStop& inside = along.inside ? along : straight;
    if (inside.seen.clearance_m >= touch_m) return inside.trajectory;
  }
  const CandidateStop& braking = saferStop(straight.seen, along.seen, touch_m) ? straight : along;
  if (braking.seen.clearance_m >= touch_m) return braking.trajectory;
  std::optional<CandidateStop> safest_swerve;
  for (Trajectory& stop : unclear_swerves) {
    CandidateStop c = examineStop(*grid, std::move(stop), clearance_m, fence, also_clear);
    if (c.inside && (!safest_swerve || saferStop(c.seen, safest_swerve->seen, touch_m)))
      safest_swerve = std::move(c);
  }
  if (safest_swerve && safest_swerve->seen.clearance_m >= touch_m) return safest_swerve->trajectory;
  return braking.trajectory;
}

}  // namespace mmh
