// Smooth bijection between an unconstrained variable tau and a positive duration T (as in
// GCOPTER): lets an unconstrained optimiser (L-BFGS) move piece durations that must stay > 0.
#pragma once

#include <cmath>

namespace mmh {

// T(tau) = 0.5 tau^2 + tau + 1 for tau > 0, 1 / (0.5 tau^2 - tau + 1) otherwise; C1 at 0.
inline double durationFromTau(double tau) {
  return tau > 0.0 ? (0.5 * tau + 1.0) * tau + 1.0 : 1.0 / ((0.5 * tau - 1.0) * tau + 1.0);
}

inline double tauFromDuration(double t) {
  // Inverse of the two branches (t >= 1 <-> tau >= 0).
  return t > 1.0 ? -1.0 + std::sqrt(2.0 * t - 1.0) : 1.0 - std::sqrt(2.0 / t - 1.0);
}

// dT/dtau.
inline double durationGradient(double tau) {
  if (tau > 0.0) return tau + 1.0;
  const double den = (0.5 * tau - 1.0) * tau + 1.0;
  return (1.0 - tau) / (den * den);
}

}  // namespace mmh
