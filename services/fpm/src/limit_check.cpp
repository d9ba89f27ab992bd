#include "mmh/fpm/limit_check.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace mmh::fpm {
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

double maxDerivativeNorm(const Piece& piece, int order, double* at_time) {
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

LimitReport measureLimits(const Trajectory& traj) {
  LimitReport r;
  double t0 = 0.0;
  for (const Piece& piece : traj.pieces()) {
    double tv = 0.0, ta = 0.0;
    const double v = maxDerivativeNorm(piece, 1, &tv);
    const double a = maxDerivativeNorm(piece, 2, &ta);
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

}  // namespace mmh::fpm
