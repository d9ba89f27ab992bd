#include "mmh/eam/cubic_roots.hpp"

#include <algorithm>
#include <cmath>

namespace mmh::eam {

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

}  // namespace mmh::eam
