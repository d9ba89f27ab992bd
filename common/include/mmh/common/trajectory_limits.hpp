// Exact maxima of |velocity| and |acceleration| of a piecewise-polynomial trajectory: the one
// routine every limit check uses (the modes' verifications, FPM's limit check, the arbiter's
// answer check, EAM's B-spline time re-allocation).
//
// Three methods, each exact up to rounding, and each kept for the callers that used it because
// their last bits differ (a different bit can change a flight):
//  - kStationaryPoints: end points and the real roots of the derivative of the squared norm
//    (polyRealRoots). Trajectory::maxSpeed / maxAcceleration; SOM and the arbiter.
//  - kBernsteinBound: branch and bound on the Bernstein coefficients of the squared norm with de
//    Casteljau subdivision; never below the true maximum, at most ~1e-9 (relative) above it, far
//    cheaper than root finding on degree-7 pieces. FPM.
//  - kCubicClosedForm: pieces of degree <= 3 in closed form (the velocity is quadratic, so the
//    stationary points of |v|^2 solve a cubic; the acceleration is linear and peaks at an end);
//    a trajectory with any piece of higher degree falls back to kStationaryPoints. EAM.
#pragma once

#include <Eigen/Core>

#include "mmh/common/polynomial.hpp"
#include "mmh/common/trajectory.hpp"

namespace mmh {

enum class MaximaMethod { kStationaryPoints, kBernsteinBound, kCubicClosedForm };

struct KinematicMaxima {
  double max_speed = 0.0, max_acc = 0.0;
  double speed_at = 0.0, acc_at = 0.0;  // trajectory times of the maxima (where known)
  // Absolute tolerance: max <= limit + tolerance.
  bool within(double v_max, double a_max, double tolerance = 1e-9) const {
    return max_speed <= v_max + tolerance && max_acc <= a_max + tolerance;
  }
};

// Maxima of speed and acceleration over the whole trajectory. kCubicClosedForm does not report
// the times (speed_at / acc_at stay 0).
KinematicMaxima trajectoryMaxima(const Trajectory& traj, MaximaMethod method);

// Maximum of |d^order p / dt^order| (order >= 1) over the whole trajectory by
// kStationaryPoints; *at_time receives where (trajectory time).
double maxDerivativeNorm(const Trajectory& traj, int order, double* at_time = nullptr);

// Maximum over one piece of |d^order p / dt^order| (order 1: speed, 2: acceleration) by
// kBernsteinBound: an upper bound never below the true maximum and at most ~1e-9 (relative)
// above it. *at_time receives where the largest sampled value lies (local time).
double bernsteinMaxDerivativeNorm(const Piece& piece, int order, double* at_time = nullptr);

// Falling factorial k (k-1) ... (k-order+1): the factor of c_k t^k in its derivative `order`.
inline double fallingFactorial(int k, int order) {
  double r = 1.0;
  for (int i = 0; i < order; ++i) r *= (k - i);
  return r;
}

// |d^order p / dt^order|^2 of a piece as a polynomial in local time.
PolyCoeffs squaredDerivativeNormPoly(const Piece& piece, int order);

// Closed-form building block of kCubicClosedForm and of EAM's B-spline maxima: the larger of
// `best` and the maximum over [0, T] of |b0 + b1 t + b2 t^2|^2 (end points and the interior
// stationary points, roots of a cubic).
double maxSquaredQuadraticNorm(const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                               const Eigen::Vector3d& b2, double T, double best);

// True when every piece has degree <= 3 (the pieces EAM produces).
bool allPiecesCubic(const Trajectory& traj);
inline bool isCubicPiece(const Piece& piece) {
  return piece.coeffs.rightCols(kMaxPolyOrder - 4).isZero(0.0);
}

// Real roots of a x^3 + b x^2 + c x + d = 0 in closed form (no allocation), degenerate leading
// coefficients included (then the quadratic or linear roots). Returns how many were written to
// roots (at most 3).
int cubicRoots(double a, double b, double c, double d, double roots[3]);

}  // namespace mmh
