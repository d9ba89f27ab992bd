#include "mmh/common/trajectory_limits.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace mmh {

namespace {

PolyCoeffs axisPoly(const PieceCoeffs& c, int axis, int order) {
  PolyCoeffs p = PolyCoeffs::Zero(std::max(1, kMaxPolyOrder - order));
  for (int k = order; k < kMaxPolyOrder; ++k)
    p[k - order] = c(axis, k) * fallingFactorial(k, order);
  return p;
}

}  // namespace

PolyCoeffs squaredDerivativeNormPoly(const Piece& piece, int order) {
  PolyCoeffs sum = PolyCoeffs::Zero(1);
  for (int axis = 0; axis < 3; ++axis) {
    PolyCoeffs p = axisPoly(piece.coeffs, axis, order);
    sum = polyAdd(sum, polyMultiply(p, p));
  }
  return sum;
}

double maxDerivativeNorm(const Trajectory& traj, int order, double* at_time) {
  double best = 0.0, best_t = 0.0, t0 = 0.0;
  for (const Piece& piece : traj.pieces()) {
    double arg = 0.0;
    double v =
        polyMaxOnInterval(squaredDerivativeNormPoly(piece, order), 0.0, piece.duration, &arg);
    if (v > best) {
      best = v;
      best_t = t0 + arg;
    }
    t0 += piece.duration;
  }
  if (at_time) *at_time = best_t;
  return std::sqrt(std::max(0.0, best));
}

// --- kBernsteinBound ----------------------------------------------------------------------
namespace {

constexpr int kMaxDegree = 2 * (kMaxPolyOrder - 2);  // squared speed of a degree-7 piece
using Coeffs = std::array<double, kMaxDegree + 1>;

struct Interval {
  Coeffs b;  // Bernstein coefficients on [u0, u1] (u = t / duration)
  double u0, u1;
  double upper;  // max of b: an upper bound of the polynomial on the interval
};

double upperOf(const Coeffs& b, int n) {
  return *std::max_element(b.begin(), b.begin() + n + 1);
}

}  // namespace

double bernsteinMaxDerivativeNorm(const Piece& piece, int order, double* at_time) {
  const double T = piece.duration;
  // Derivative in u = t / T (on [0, 1]): coefficient of u^j is c_(j+order) ff T^j per axis,
  // with ff the falling factorial (j + order)! / j!.
  Eigen::Matrix<double, 3, kMaxPolyOrder> d = Eigen::Matrix<double, 3, kMaxPolyOrder>::Zero();
  int deg = -1;
  double Tj = 1.0;
  for (int j = 0; j + order < kMaxPolyOrder; ++j, Tj *= T) {
    double ff = 1.0;
    for (int i = 1; i <= order; ++i) ff *= (j + i);
    d.col(j) = piece.coeffs.col(j + order) * (ff * Tj);
    if (!d.col(j).isZero()) deg = j;
  }
  if (deg < 0) {
    if (at_time) *at_time = 0.0;
    return 0.0;
  }
  // Squared norm in u: degree n = 2 deg.
  const int n = 2 * deg;
  Coeffs a{};
  for (int axis = 0; axis < 3; ++axis)
    for (int i = 0; i <= deg; ++i)
      for (int j = 0; j <= deg; ++j) a[i + j] += d(axis, i) * d(axis, j);
  // Monomial -> Bernstein: b_i = sum_{k <= i} C(i, k) / C(n, k) a_k.
  static const auto binom = [] {
    std::array<std::array<double, kMaxDegree + 1>, kMaxDegree + 1> c{};
    for (int i = 0; i <= kMaxDegree; ++i) {
      c[i][0] = 1.0;
      for (int k = 1; k <= i; ++k) c[i][k] = c[i - 1][k - 1] + (k <= i - 1 ? c[i - 1][k] : 0.0);
    }
    return c;
  }();
  Interval root;
  root.u0 = 0.0;
  root.u1 = 1.0;
  root.b.fill(0.0);
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k <= i; ++k) root.b[i] += binom[i][k] / binom[n][k] * a[k];
  root.upper = upperOf(root.b, n);
  double lower = root.b[0], arg = 0.0;
  if (root.b[n] > lower) {
    lower = root.b[n];
    arg = 1.0;
  }
  // Branch and bound: `lower` is the largest exact value seen (end coefficients are values of
  // the polynomial), intervals whose bound cannot exceed it by more than `tol` are settled, and
  // the answer is the largest bound left - never below the true maximum, at most tol above it.
  double settled = lower;
  std::array<Interval, 64> stack;
  int top = 0;
  stack[top++] = root;
  int work = 0;
  while (top > 0 && work < 4000) {
    ++work;
    const Interval iv = stack[--top];
    const double tol = 1e-9 * std::max(1.0, lower);
    if (iv.upper <= lower + tol) {  // cannot raise the maximum noticeably
      settled = std::max(settled, iv.upper);
      continue;
    }
    // de Casteljau at the middle.
    Interval left, right;
    left.b.fill(0.0);
    right.b.fill(0.0);
    Coeffs w = iv.b;
    for (int r = 0; r <= n; ++r) {
      left.b[r] = w[0];
      right.b[n - r] = w[n - r];
      for (int i = 0; i < n - r; ++i) w[i] = 0.5 * (w[i] + w[i + 1]);
    }
    const double mid = 0.5 * (iv.u0 + iv.u1);
    left.u0 = iv.u0;
    left.u1 = mid;
    right.u0 = mid;
    right.u1 = iv.u1;
    if (left.b[n] > lower) {  // the value at the midpoint
      lower = left.b[n];
      arg = mid;
    }
    left.upper = upperOf(left.b, n);
    right.upper = upperOf(right.b, n);
    if (top + 2 > static_cast<int>(stack.size()) || iv.u1 - iv.u0 < 1e-12) {
      // Out of room or precision: keep the bound, which is conservative.
      settled = std::max(settled, std::max(left.upper, right.upper));
      continue;
    }
    // Push the more promising half last so it is explored first.
    if (left.upper > right.upper) {
      stack[top++] = right;
      stack[top++] = left;
    } else {
      stack[top++] = left;
      stack[top++] = right;
    }
  }
  // Work limit reached: the remaining bounds count (conservative).
  for (int i = 0; i < top; ++i) settled = std::max(settled, stack[i].upper);
  if (at_time) *at_time = arg * T;
  return std::sqrt(std::max({0.0, lower, settled}));
}

// --- kCubicClosedForm -------------------------------------------------------------------

int cubicRoots(double a, double b, double c, double d, double roots[3]) {
  const double scale = std::max({std::abs(a), std::abs(b), std::abs(c), std::abs(d)});
  if (scale == 0.0) return 0;
  if (std::abs(a) < 1e-12 * scale) {
    if (std::abs(b) < 1e-12 * scale) {
      if (std::abs(c) < 1e-12 * scale) return 0;
      roots[0] = -d / c;
      return 1;
    }
    const double disc = c * c - 4.0 * b * d;
    if (disc < 0.0) return 0;
    const double sq = std::sqrt(disc);
    roots[0] = (-c + sq) / (2.0 * b);
    roots[1] = (-c - sq) / (2.0 * b);
    return 2;
  }
  const double B = b / a, C = c / a, D = d / a;
  const double p = C - B * B / 3.0, q = 2.0 * B * B * B / 27.0 - B * C / 3.0 + D;
  const double disc = 0.25 * q * q + p * p * p / 27.0;
  int n = 0;
  if (disc > 0.0) {
    const double sq = std::sqrt(disc);
    roots[n++] = std::cbrt(-0.5 * q + sq) + std::cbrt(-0.5 * q - sq) - B / 3.0;
  } else {
    const double r = std::sqrt(std::max(0.0, -p / 3.0));
    const double cos_arg = r > 0.0 ? std::clamp(-q / (2.0 * r * r * r), -1.0, 1.0) : 0.0;
    const double phi = std::acos(cos_arg);
    for (int k = 0; k < 3; ++k)
      roots[n++] = 2.0 * r * std::cos((phi + 2.0 * M_PI * k) / 3.0) - B / 3.0;
  }
  for (int i = 0; i < n; ++i) {  // polish
    for (int it = 0; it < 2; ++it) {
      const double x = roots[i];
      const double f = ((a * x + b) * x + c) * x + d, df = (3.0 * a * x + 2.0 * b) * x + c;
      if (df != 0.0) roots[i] = x - f / df;
    }
  }
  return n;
}

double maxSquaredQuadraticNorm(const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                               const Eigen::Vector3d& b2, double T, double best) {
  auto norm2 = [&](double t) { return (b0 + t * (b1 + t * b2)).squaredNorm(); };
  double v2 = std::max({best, norm2(0.0), norm2(T)});
  // Stationary points of |v|^2 solve v . v' = 0, a cubic.
  double roots[3];
  const int n = cubicRoots(2.0 * b2.dot(b2), 3.0 * b1.dot(b2), b1.dot(b1) + 2.0 * b0.dot(b2),
                           b0.dot(b1), roots);
  for (int i = 0; i < n; ++i) {
    if (roots[i] > 0.0 && roots[i] < T) v2 = std::max(v2, norm2(roots[i]));
  }
  return v2;
}

bool allPiecesCubic(const Trajectory& traj) {
  for (const Piece& piece : traj.pieces()) {
    if (!isCubicPiece(piece)) return false;
  }
  return true;
}

namespace {

KinematicMaxima cubicClosedFormMaxima(const Trajectory& traj) {
  double v2 = 0.0, a2 = 0.0;
  for (const Piece& piece : traj.pieces()) {
    const double T = piece.duration;
    const Eigen::Vector3d b0 = piece.coeffs.col(1), b1 = 2.0 * piece.coeffs.col(2),
                          b2 = 3.0 * piece.coeffs.col(3);
    v2 = maxSquaredQuadraticNorm(b0, b1, b2, T, v2);
    a2 = std::max({a2, b1.squaredNorm(), (b1 + 2.0 * T * b2).squaredNorm()});
  }
  KinematicMaxima m;
  m.max_speed = std::sqrt(v2);
  m.max_acc = std::sqrt(a2);
  return m;
}

KinematicMaxima bernsteinMaxima(const Trajectory& traj) {
  KinematicMaxima r;
  double t0 = 0.0;
  for (const Piece& piece : traj.pieces()) {
    double tv = 0.0, ta = 0.0;
    const double v = bernsteinMaxDerivativeNorm(piece, 1, &tv);
    const double a = bernsteinMaxDerivativeNorm(piece, 2, &ta);
    if (v > r.max_speed) {
      r.max_speed = v;
      r.speed_at = t0 + tv;
    }
    if (a > r.max_acc) {
      r.max_acc = a;
      r.acc_at = t0 + ta;
    }
    t0 += piece.duration;
  }
  return r;
}

}  // namespace

KinematicMaxima trajectoryMaxima(const Trajectory& traj, MaximaMethod method) {
  if (method == MaximaMethod::kBernsteinBound) return bernsteinMaxima(traj);
  if (method == MaximaMethod::kCubicClosedForm && allPiecesCubic(traj))
    return cubicClosedFormMaxima(traj);
  KinematicMaxima m;
  m.max_speed = maxDerivativeNorm(traj, 1, &m.speed_at);
  m.max_acc = maxDerivativeNorm(traj, 2, &m.acc_at);
  return m;
}

}  // namespace mmh
