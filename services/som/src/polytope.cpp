#include "mmh/som/polytope.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mmh::som {

bool Polytope::addHalfspace(const Eigen::Vector3d& a, double b) {
  const double n = a.norm();
  if (!(n > 0.0) || !std::isfinite(b / n)) return false;
  h_.conservativeResize(h_.rows() + 1, Eigen::NoChange);
  h_.row(h_.rows() - 1) << a.transpose() / n, b / n;
  return true;
}

void Polytope::addBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  for (int i = 0; i < 3; ++i) {
    addHalfspace(Eigen::Vector3d::Unit(i), hi[i]);
    addHalfspace(-Eigen::Vector3d::Unit(i), -lo[i]);
  }
}

double Polytope::maxViolation(const Eigen::Vector3d& p) const {
  // A plain loop: the Eigen expression would evaluate the product into a heap temporary.
  double worst = -std::numeric_limits<double>::infinity();
  const int n = static_cast<int>(h_.rows());
  const double* a0 = h_.col(0).data();
  const double *a1 = h_.col(1).data(), *a2 = h_.col(2).data(), *b = h_.col(3).data();
  for (int i = 0; i < n; ++i)
    worst = std::max(worst, a0[i] * p.x() + a1[i] * p.y() + a2[i] * p.z() - b[i]);
  return worst;
}

bool Polytope::lineInterval(const Eigen::Vector3d& p, int axis, double* lo, double* hi) const {
  double l = -std::numeric_limits<double>::infinity(), u = std::numeric_limits<double>::infinity();
  for (int i = 0; i < h_.rows(); ++i) {
    const double slack = h_(i, 3) - h_.row(i).head<3>().dot(p);
    const double c = h_(i, axis);
    if (c > 1e-12) {
      u = std::min(u, slack / c);
    } else if (c < -1e-12) {
      l = std::max(l, slack / c);
    } else if (slack < 0.0) {
      return false;
    }
  }
  *lo = l;
  *hi = u;
  return l <= u;
}

}  // namespace mmh::som
