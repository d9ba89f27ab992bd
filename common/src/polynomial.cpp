#include "mmh/common/polynomial.hpp"

#include <algorithm>
#include <cmath>

namespace mmh {
namespace {

// Degree after dropping negligible leading coefficients.
int effectiveDegree(const PolyCoeffs& c) {
  double scale = c.cwiseAbs().maxCoeff();
  if (scale == 0.0) return -1;
  for (int k = static_cast<int>(c.size()) - 1; k >= 0; --k) {
    if (std::abs(c[k]) > 1e-14 * scale) return k;
  }
  return -1;
}

// Root of a polynomial that is monotone on [a, b] with f(a), f(b) of opposite signs.
double refineRoot(const PolyCoeffs& c, const PolyCoeffs& dc, double a, double b, double fa) {
  double lo = a, hi = b;
  double x = 0.5 * (a + b);
  for (int it = 0; it < 100; ++it) {
    double fx = polyEval(c, x);
    if (fx == 0.0) return x;
    if ((fx < 0.0) == (fa < 0.0)) {
      lo = x;
    } else {
      hi = x;
    }
    double d = polyEval(dc, x);
    double newton = d != 0.0 ? x - fx / d : lo - 1.0;
    x = (newton > lo && newton < hi) ? newton : 0.5 * (lo + hi);
    if (hi - lo < 1e-13 * std::max(1.0, std::abs(x))) break;
  }
  return x;
}

}  // namespace

double polyEval(const PolyCoeffs& c, double t) {
  double r = 0.0;
  for (int k = static_cast<int>(c.size()) - 1; k >= 0; --k) r = r * t + c[k];
  return r;
}

PolyCoeffs polyDerivative(const PolyCoeffs& c) {
  if (c.size() <= 1) return PolyCoeffs::Zero(1);
  PolyCoeffs d(c.size() - 1);
  for (int k = 1; k < c.size(); ++k) d[k - 1] = k * c[k];
  return d;
}

PolyCoeffs polyMultiply(const PolyCoeffs& a, const PolyCoeffs& b) {
  PolyCoeffs r = PolyCoeffs::Zero(a.size() + b.size() - 1);
  for (int i = 0; i < a.size(); ++i)
    for (int j = 0; j < b.size(); ++j) r[i + j] += a[i] * b[j];
  return r;
}

PolyCoeffs polyAdd(const PolyCoeffs& a, const PolyCoeffs& b) {
  PolyCoeffs r = PolyCoeffs::Zero(std::max(a.size(), b.size()));
  r.head(a.size()) += a;
  r.head(b.size()) += b;
  return r;
}

double polyIntegral(const PolyCoeffs& c, double t) {
  double r = 0.0;
  for (int k = static_cast<int>(c.size()) - 1; k >= 0; --k) r = r * t + c[k] / (k + 1);
  return r * t;
}

std::vector<double> polyRealRoots(const PolyCoeffs& c, double lo, double hi) {
  std::vector<double> roots;
  int deg = effectiveDegree(c);
  if (deg <= 0 || !(hi > lo)) return roots;
  PolyCoeffs p = c.head(deg + 1);
  PolyCoeffs dp = polyDerivative(p);
  // Split [lo, hi] at the stationary points: between two of them p is monotone.
  std::vector<double> knots{lo};
  for (double s : polyRealRoots(dp, lo, hi)) knots.push_back(s);
  knots.push_back(hi);
  const double tol = 1e-12 * std::max(1.0, p.cwiseAbs().maxCoeff());
  for (size_t i = 0; i + 1 < knots.size(); ++i) {
    double a = knots[i], b = knots[i + 1];
    double fa = polyEval(p, a), fb = polyEval(p, b);
    if (std::abs(fa) <= tol) {
      if (roots.empty() || std::abs(roots.back() - a) > 1e-9) roots.push_back(a);
      continue;
    }
    if (std::abs(fb) <= tol) continue;  // picked up as the next interval's start (or hi below)
    if ((fa < 0.0) != (fb < 0.0)) roots.push_back(refineRoot(p, dp, a, b, fa));
  }
  if (std::abs(polyEval(p, hi)) <= tol && (roots.empty() || std::abs(roots.back() - hi) > 1e-9))
    roots.push_back(hi);
  return roots;
}

double polyMaxOnInterval(const PolyCoeffs& c, double lo, double hi, double* argmax) {
  double best_t = lo;
  double best = polyEval(c, lo);
  auto consider = [&](double t) {
    double v = polyEval(c, t);
    if (v > best) {
      best = v;
      best_t = t;
    }
  };
  consider(hi);
  for (double t : polyRealRoots(polyDerivative(c), lo, hi)) consider(t);
  if (argmax) *argmax = best_t;
  return best;
}

}  // namespace mmh
