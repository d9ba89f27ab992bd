// Uniform cubic B-spline in 3-D, the trajectory representation EAM optimises: evaluation by
// de Boor's algorithm, the control points that reproduce a start state exactly, and the exact
// conversion to the project's polynomial pieces (one cubic per knot interval).
#pragma once

#include <Eigen/Core>

#include "mmh/common/trajectory.hpp"

namespace mmh::eam {

class UniformBspline {
 public:
  static constexpr int kDegree = 3;

  UniformBspline() = default;
  // Control points Q_0..Q_{K+2} as columns (K >= 1 segments), knot span dt > 0. The curve is
  // defined on [0, K dt]; segment i (time [i dt, (i+1) dt]) depends on Q_i..Q_{i+3}.
  UniformBspline(Eigen::Matrix3Xd control_points, double knot_span);

  const Eigen::Matrix3Xd& controlPoints() const { return q_; }
  Eigen::Matrix3Xd& controlPoints() { return q_; }
  double knotSpan() const { return dt_; }
  void setKnotSpan(double dt) { dt_ = dt; }
  int numControlPoints() const { return static_cast<int>(q_.cols()); }
  int numSegments() const { return numControlPoints() - kDegree; }
  double duration() const { return numSegments() * dt_; }

  // Derivative `order` (0..3) at time t (clamped to [0, duration()]), evaluated directly from
  // the control points of the derivative spline by de Boor's recursion (independent of
  // toTrajectory(), so the two can check each other).
  Eigen::Vector3d evaluate(int order, double t) const;

  // The same curve as polynomial pieces: exact (up to rounding), one cubic per knot interval.
  Trajectory toTrajectory() const;

  // Q_0, Q_1, Q_2 (columns) such that the curve starts with exactly this position, velocity
  // and acceleration for knot span dt:
  //   p = (Q0 + 4 Q1 + Q2) / 6,  v = (Q2 - Q0) / (2 dt),  a = (Q0 - 2 Q1 + Q2) / dt^2.
  static Eigen::Matrix3d startControlPoints(const KinematicState& start, double dt);

 private:
  Eigen::Matrix3Xd q_;
  double dt_ = 0.1;
};

}  // namespace mmh::eam
