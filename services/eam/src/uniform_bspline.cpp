#include "mmh/eam/uniform_bspline.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mmh::eam {

UniformBspline::UniformBspline(Eigen::Matrix3Xd control_points, double knot_span)
    : q_(std::move(control_points)), dt_(knot_span) {
  if (q_.cols() < kDegree + 1) throw std::invalid_argument("a cubic B-spline needs 4 points");
  if (!(knot_span > 0.0)) throw std::invalid_argument("knot span must be positive");
}

Eigen::Vector3d UniformBspline::evaluate(int order, double t) const {
  if (order < 0 || order > kDegree) return Eigen::Vector3d::Zero();
  // Control points of the order-th derivative: repeated differences / dt. Each derivative of a
  // uniform B-spline is again uniform, one degree lower, on the same time interval.
  Eigen::Matrix3Xd p = q_;
  for (int r = 0; r < order; ++r) {
    Eigen::Matrix3Xd d(3, p.cols() - 1);
    for (int i = 0; i + 1 < p.cols(); ++i) d.col(i) = (p.col(i + 1) - p.col(i)) / dt_;
    p = d;
  }
  const int degree = kDegree - order;
  // Knots u_j = (j - degree) dt, j = 0 .. n + degree + 1 for control points P_0..P_n; the
  // valid interval [u_degree, u_{n+1}] is [0, K dt].
  const int n = static_cast<int>(p.cols()) - 1;
  t = std::clamp(t, 0.0, duration());
  int k = degree + static_cast<int>(std::floor(t / dt_));  // u_k <= t < u_{k+1}
  k = std::clamp(k, degree, n);
  auto knot = [&](int j) { return (j - degree) * dt_; };
  Eigen::Matrix3Xd d(3, degree + 1);
  for (int j = 0; j <= degree; ++j) d.col(j) = p.col(j + k - degree);
  for (int r = 1; r <= degree; ++r) {
    for (int j = degree; j >= r; --j) {
      const double lo = knot(j + k - degree), hi = knot(j + 1 + k - r);
      const double alpha = (t - lo) / (hi - lo);
      d.col(j) = (1.0 - alpha) * d.col(j - 1) + alpha * d.col(j);
    }
  }
  return d.col(degree);
}

Trajectory UniformBspline::toTrajectory() const {
  // Segment i in local time s = t / dt: p(s) = [1 s s^2 s^3] M [Q_i Q_{i+1} Q_{i+2} Q_{i+3}]^T;
  // the coefficient of t^k is row k of M times the points, divided by dt^k.
  static const double m[4][4] = {{1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0, 0.0},
                                 {-3.0 / 6.0, 0.0, 3.0 / 6.0, 0.0},
                                 {3.0 / 6.0, -6.0 / 6.0, 3.0 / 6.0, 0.0},
                                 {-1.0 / 6.0, 3.0 / 6.0, -3.0 / 6.0, 1.0 / 6.0}};
  std::vector<Piece> pieces(numSegments());
  for (int i = 0; i < numSegments(); ++i) {
    Piece& piece = pieces[i];
    piece.duration = dt_;
    double scale = 1.0;
    for (int k = 0; k < 4; ++k) {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (int j = 0; j < 4; ++j) c += m[k][j] * q_.col(i + j);
      piece.coeffs.col(k) = c / scale;
      scale *= dt_;
    }
  }
  return Trajectory(std::move(pieces));
}

Eigen::Matrix3d UniformBspline::startControlPoints(const KinematicState& start, double dt) {
  // Solving the three equations of the header for Q0, Q1, Q2.
  const Eigen::Vector3d& p = start.position;
  const Eigen::Vector3d& v = start.velocity;
  const Eigen::Vector3d& a = start.acceleration;
  Eigen::Matrix3d q;
  q.col(0) = p - dt * v + dt * dt / 3.0 * a;
  q.col(1) = p - dt * dt / 6.0 * a;
  q.col(2) = p + dt * v + dt * dt / 3.0 * a;
  return q;
}

}  // namespace mmh::eam
