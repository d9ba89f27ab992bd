// Proof that a trajectory keeps |v| <= v_max and |a| <= a_max at every instant, not just at
// samples. Per piece the squared norm is a polynomial; written in the Bernstein basis of an
// interval its coefficients bound it from above (convex hull property) and its end coefficients
// are exact values. Branch and bound with de Casteljau subdivision pins the maximum to within a
// tiny tolerance, so the answer is exact up to that tolerance (and far cheaper than root finding).
#pragma once

#include "mmh/common/trajectory.hpp"

namespace mmh::fpm {

// Maximum over the piece of |d^order p / dt^order| (order 1: speed, 2: acceleration): an upper
// bound that is never below the true maximum and at most ~1e-9 (relative) above it. *at_time
// receives where the largest sampled value lies (local time).
double maxDerivativeNorm(const Piece& piece, int order, double* at_time = nullptr);

struct LimitReport {
  double max_speed = 0.0, max_acc = 0.0;
  double speed_at = 0.0, acc_at = 0.0;  // trajectory times of the maxima
  bool within(double v_max, double a_max, double tolerance = 1e-9) const {
    return max_speed <= v_max + tolerance && max_acc <= a_max + tolerance;
  }
};

LimitReport measureLimits(const Trajectory& traj);

}  // namespace mmh::fpm
