#include "mmh/eam/bspline_cost.hpp"

#include <algorithm>
#include <cmath>

namespace mmh::eam {

CostSettings costSettingsFor(const EamParams& p) {
  CostSettings s;
  s.max_vel_mps = p.max_vel_mps;
  s.max_acc_mps2 = p.max_acc_mps2;
  // Walls inside the fence, but never crossing: a fence thinner than twice the margin keeps its
  // middle.
  const Eigen::Vector3d margin =
      Eigen::Vector3d::Constant(p.geofence_margin_m)
          .cwiseMin(0.5 * (p.geofence_max - p.geofence_min).cwiseMax(0.0));
  s.box_min = p.geofence_min + margin;
  s.box_max = p.geofence_max - margin;
  return s;
}

double collisionPenalty(double c, double clearance, double* derivative) {
  if (c <= 0.0) {
    *derivative = 0.0;
    return 0.0;
  }
  if (c <= clearance || clearance <= 0.0) {
    *derivative = 3.0 * c * c;
    return c * c * c;
  }
  // Beyond the clearance the cubic would make the gradient explode for deep points; continue it
  // as the quadratic with the same value, slope and curvature at c = clearance.
  const double sf = clearance;
  *derivative = 6.0 * sf * c - 3.0 * sf * sf;
  return 3.0 * sf * c * c - 3.0 * sf * sf * c + sf * sf * sf;
}

CostTerms BsplineCost::evaluate(const Eigen::Matrix3Xd& q, double dt, Eigen::Matrix3Xd* grad,
                                int first, int last) const {
  const int n = static_cast<int>(q.cols());
  first = std::max(first, 0);
  last = std::min(last, n - 1);
  if (grad) {
    // Terms that involve [first, last] write at most 3 columns beyond it.
    if (grad->cols() != n) grad->resize(3, n);
    const int lo = std::max(0, first - 3), hi = std::min(n - 1, last + 3);
    grad->middleCols(lo, hi - lo + 1).setZero();
  }
  CostTerms t;
  t.smooth = smoothness(q, dt, grad, weights_.smooth, first, last);
  t.collision = collision(q, grad, weights_.collision, first, last);
  t.feasibility = feasibility(q, dt, grad, weights_.feasibility, first, last);
  t.total = weights_.smooth * t.smooth + weights_.collision * t.collision +
            weights_.feasibility * t.feasibility;
  return t;
}

double BsplineCost::smoothness(const Eigen::Matrix3Xd& q, double dt, Eigen::Matrix3Xd* grad,
                               double weight, int first, int last) const {
  // Jerk on interval i is (Q_{i+3} - 3 Q_{i+2} + 3 Q_{i+1} - Q_i) / dt^3, constant; its squared
  // norm integrated over dt gives |d|^2 / dt^5.
  const double scale = 1.0 / std::pow(dt, 5);
  double cost = 0.0;
  const int end = std::min(static_cast<int>(q.cols()) - 4, last);
  for (int i = std::max(0, first - 3); i <= end; ++i) {
    const Eigen::Vector3d d = q.col(i + 3) - 3.0 * q.col(i + 2) + 3.0 * q.col(i + 1) - q.col(i);
    cost += d.squaredNorm();
    if (grad) {
      const Eigen::Vector3d g = 2.0 * weight * scale * d;
      grad->col(i + 3) += g;
      grad->col(i + 2) -= 3.0 * g;
      grad->col(i + 1) += 3.0 * g;
      grad->col(i) -= g;
    }
  }
  return cost * scale;
}

double BsplineCost::collision(const Eigen::Matrix3Xd& q, Eigen::Matrix3Xd* grad, double weight,
                              int first, int last) const {
  double cost = 0.0;
  if (pairs_) {
    const int end = std::min(static_cast<int>(pairs_->size()) - 1, last);
    for (int i = first; i <= end; ++i) {
      for (const AnchorPair& pair : (*pairs_)[i]) {
        const double d = (q.col(i) - pair.p).dot(pair.v);
        double dc = 0.0;
        cost += collisionPenalty(pair.clearance - d, pair.clearance, &dc);
        if (grad && dc != 0.0) grad->col(i) -= weight * dc * pair.v;  // dc/dQ = -v
      }
    }
  }
  // The geofence box: a wall on each face (the curve stays inside when its control points do).
  for (int i = first; i <= last; ++i) {
    for (int a = 0; a < 3; ++a) {
      const double below = settings_.box_min[a] - q(a, i);
      const double above = q(a, i) - settings_.box_max[a];
      if (below > 0.0) {
        cost += below * below * below;
        if (grad) (*grad)(a, i) -= weight * 3.0 * below * below;
      } else if (above > 0.0) {
        cost += above * above * above;
        if (grad) (*grad)(a, i) += weight * 3.0 * above * above;
      }
    }
  }
  return cost;
}

double BsplineCost::feasibility(const Eigen::Matrix3Xd& q, double dt, Eigen::Matrix3Xd* grad,
                                double weight, int first, int last) const {
  double cost = 0.0;
  const double v2 = settings_.max_vel_mps * settings_.max_vel_mps;
  const double a2 = settings_.max_acc_mps2 * settings_.max_acc_mps2;
  const double inv_dt = 1.0 / dt, inv_dt2 = inv_dt * inv_dt;
  const int n = static_cast<int>(q.cols());
  for (int i = std::max(0, first - 1); i <= std::min(n - 2, last); ++i) {
    const Eigen::Vector3d v = (q.col(i + 1) - q.col(i)) * inv_dt;
    const double e = v.squaredNorm() - v2;
    if (e <= 0.0) continue;
    cost += e * e;
    if (grad) {
      const Eigen::Vector3d g = weight * 4.0 * e * v * inv_dt;  // d(e^2)/dV = 4 e V
      grad->col(i + 1) += g;
      grad->col(i) -= g;
    }
  }
  for (int i = std::max(0, first - 2); i <= std::min(n - 3, last); ++i) {
    const Eigen::Vector3d a = (q.col(i + 2) - 2.0 * q.col(i + 1) + q.col(i)) * inv_dt2;
    const double e = a.squaredNorm() - a2;
    if (e <= 0.0) continue;
    cost += e * e;
    if (grad) {
      const Eigen::Vector3d g = weight * 4.0 * e * a * inv_dt2;
      grad->col(i + 2) += g;
      grad->col(i + 1) -= 2.0 * g;
      grad->col(i) += g;
    }
  }
  return cost;
}

}  // namespace mmh::eam
