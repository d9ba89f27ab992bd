#include "mmh/eam/initial_guess.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mmh::eam {
namespace {

Piece quinticPiece(const KinematicState& s, const Eigen::Vector3d& target, double T) {
  // Boundary conditions p, v, a at 0 and (target, 0, 0) at T.
  const Eigen::Vector3d d = target - s.position;
  const double T2 = T * T, T3 = T2 * T, T4 = T3 * T, T5 = T4 * T;
  Piece piece;
  piece.duration = T;
  piece.coeffs.col(0) = s.position;
  piece.coeffs.col(1) = s.velocity;
  piece.coeffs.col(2) = 0.5 * s.acceleration;
  piece.coeffs.col(3) = (20.0 * d - 12.0 * s.velocity * T - 3.0 * s.acceleration * T2) / (2.0 * T3);
  piece.coeffs.col(4) =
      (-30.0 * d + 16.0 * s.velocity * T + 3.0 * s.acceleration * T2) / (2.0 * T4);
  piece.coeffs.col(5) = (12.0 * d - 6.0 * s.velocity * T - s.acceleration * T2) / (2.0 * T5);
  return piece;
}

}  // namespace

Trajectory straightQuintic(const KinematicState& start, const Eigen::Vector3d& target,
                           double max_vel_mps, double max_acc_mps2) {
  const double dist = (target - start.position).norm();
  const double vlim = std::max(max_vel_mps, start.velocity.norm()) * (1.0 + 1e-6);
  const double alim = std::max(max_acc_mps2, start.acceleration.norm()) * (1.0 + 1e-6);
  // Lower bound: no rest-to-rest curve covers dist faster than at constant v_max.
  double T = std::max({0.2, dist / max_vel_mps, start.velocity.norm() / max_acc_mps2});
  // Longer is not always better: from a moving start a long quintic first flies on with the
  // start velocity and comes back, so its speed grows again. Keep the least-violating duration
  // (a guess only; the optimiser and the time re-allocation enforce the limits).
  Trajectory best;
  double best_excess = std::numeric_limits<double>::infinity();
  for (int iter = 0; iter < 40; ++iter, T *= 1.1) {
    Trajectory traj({quinticPiece(start, target, T)});
    const double excess = std::max(traj.maxSpeed() / vlim, traj.maxAcceleration() / alim);
    if (excess < best_excess) {
      best_excess = excess;
      best = std::move(traj);
    }
    if (excess <= 1.0) break;
  }
  return best;
}

UniformBspline sampleToBspline(const Trajectory& guess, const KinematicState& start,
                               const Eigen::Vector3d& target, double knot_span_s, int min_segments,
                               int max_segments) {
  const double T = std::max(1e-3, guess.duration());
  const int K =
      std::clamp(static_cast<int>(std::ceil(T / knot_span_s - 1e-9)), min_segments, max_segments);
  const double dt = T / K;
  Eigen::Matrix3Xd q(3, K + 3);
  q.leftCols(3) = UniformBspline::startControlPoints(start, dt);
  for (int i = 3; i < K; ++i) {
    const double t = (i - 1) * dt;
    q.col(i) = guess.position(t) - dt * dt / 6.0 * guess.acceleration(t);
  }
  for (int i = K; i < K + 3; ++i) q.col(i) = target;
  return UniformBspline(q, dt);
}

}  // namespace mmh::eam

namespace mmh::eam {

UniformBspline sampleAlongPath(const std::vector<Eigen::Vector3d>& path,
                               const KinematicState& start, const Eigen::Vector3d& target,
                               double knot_span_s, double max_vel_mps, double max_acc_mps2,
                               int min_segments, int max_segments) {
  std::vector<double> cumulative(1, 0.0);
  for (size_t k = 1; k < path.size(); ++k)
    cumulative.push_back(cumulative.back() + (path[k] - path[k - 1]).norm());
  const double length = cumulative.back();
  // Speed profile along the path: from the start's speed (at most v_max) up to v_max at a_max,
  // then down to rest at a_max; a triangle when the path is too short for v_max.
  const double v0 = std::min(start.velocity.norm(), max_vel_mps);
  const double a = max_acc_mps2;
  double vc = max_vel_mps;
  const double d_full = (vc * vc - v0 * v0) / (2.0 * a) + vc * vc / (2.0 * a);
  if (d_full > length) vc = std::max(v0, std::sqrt(std::max(0.0, a * length + 0.5 * v0 * v0)));
  const double t_up = (vc - v0) / a, d_up = (vc * vc - v0 * v0) / (2.0 * a);
  const double d_down = vc * vc / (2.0 * a), t_down = vc / a;
  const double d_cruise = std::max(0.0, length - d_up - d_down);
  const double t_cruise = vc > 0.0 ? d_cruise / vc : 0.0;
  const double T = std::max(1e-3, t_up + t_cruise + t_down);
  auto arc = [&](double t) {
    if (t <= t_up) return v0 * t + 0.5 * a * t * t;
    if (t <= t_up + t_cruise) return d_up + vc * (t - t_up);
    const double u = std::min(t - t_up - t_cruise, t_down);
    return std::min(length, d_up + d_cruise + vc * u - 0.5 * a * u * u);
  };
  auto pointAt = [&](double s) {
    for (size_t k = 0; k + 1 < path.size(); ++k) {
      const double len = cumulative[k + 1] - cumulative[k];
      if (s <= cumulative[k + 1] || k + 2 == path.size())
        return Eigen::Vector3d(
            path[k] + (path[k + 1] - path[k]) *
                          (len > 0.0 ? std::clamp((s - cumulative[k]) / len, 0.0, 1.0) : 0.0));
    }
    return path.back();
  };
  const int K =
      std::clamp(static_cast<int>(std::ceil(T / knot_span_s - 1e-9)), min_segments, max_segments);
  const double dt = T / K;
  Eigen::Matrix3Xd q(3, K + 3);
  q.leftCols(3) = UniformBspline::startControlPoints(start, dt);
  for (int i = 3; i < K; ++i) q.col(i) = path.size() < 2 ? target : pointAt(arc((i - 1) * dt));
  for (int i = K; i < K + 3; ++i) q.col(i) = target;
  return UniformBspline(q, dt);
}

}  // namespace mmh::eam
