#include "mmh/sim/elliptic_ring.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mmh::sim {
namespace {

// Sphere tracing stops this close to the surface; a ray that needs more steps than kMaxSteps
// is only grazing the tube and counts as a miss.
constexpr double kSurfaceTolerance = 1e-4;
constexpr int kMaxSteps = 256;

// The ring's local frame: u along the horizontal in-plane axis, v along z, w along the normal.
Eigen::Vector3d toLocal(const EllipticRing& ring, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = p - ring.center;
  const double c = std::cos(ring.yaw), s = std::sin(ring.yaw);
  return Eigen::Vector3d(-s * d.x() + c * d.y(), d.z(), c * d.x() + s * d.y());
}

// Root s of (r0 z0 / (s + r0))^2 + (z1 / (s + 1))^2 = 1 on the bracket where it is unique.
double footPointParameter(double r0, double z0, double z1, double g) {
  const double n0 = r0 * z0;
  double s0 = z1 - 1.0;
  double s1 = g < 0.0 ? 0.0 : std::hypot(n0, z1) - 1.0;
  double s = 0.0;
  for (int i = 0; i < 200; ++i) {
    s = 0.5 * (s0 + s1);
    if (s == s0 || s == s1) break;
    const double ratio0 = n0 / (s + r0), ratio1 = z1 / (s + 1.0);
    const double value = ratio0 * ratio0 + ratio1 * ratio1 - 1.0;
    if (value > 0.0)
      s0 = s;
    else if (value < 0.0)
      s1 = s;
    else
      break;
  }
  return s;
}

}  // namespace

double EllipticRing::boundingRadius() const {
  return std::max(semi_horizontal_m, semi_vertical_m) + tube_radius_m;
}

double distanceToEllipseCurve(double a, double b, double u, double v) {
  // By symmetry the first quadrant, with the longer semi-axis first.
  double e0 = a, e1 = b, y0 = std::abs(u), y1 = std::abs(v);
  if (e0 < e1) {
    std::swap(e0, e1);
    std::swap(y0, y1);
  }
  if (y1 > 0.0) {
    if (y0 > 0.0) {
      const double z0 = y0 / e0, z1 = y1 / e1;
      const double g = z0 * z0 + z1 * z1 - 1.0;
      if (g == 0.0) return 0.0;
      const double r0 = (e0 / e1) * (e0 / e1);
      const double s = footPointParameter(r0, z0, z1, g);
      const double x0 = r0 * y0 / (s + r0), x1 = y1 / (s + 1.0);
      return std::hypot(x0 - y0, x1 - y1);
    }
    return std::abs(y1 - e1);
  }
  // On the long axis: the foot point leaves the axis when the point is inside the evolute.
  const double numer0 = e0 * y0, denom0 = e0 * e0 - e1 * e1;
  if (numer0 < denom0) {
    const double xde0 = numer0 / denom0;
    const double x0 = e0 * xde0, x1 = e1 * std::sqrt(std::max(0.0, 1.0 - xde0 * xde0));
    return std::hypot(x0 - y0, x1);
  }
  return std::abs(y0 - e0);
}

double distanceToRing(const EllipticRing& ring, const Eigen::Vector3d& p) {
  const Eigen::Vector3d l = toLocal(ring, p);
  // Every point of the curve lies in the plane w = 0, so the in-plane and normal offsets add in
  // quadrature.
  const double in_plane =
      distanceToEllipseCurve(ring.semi_horizontal_m, ring.semi_vertical_m, l.x(), l.y());
  return std::hypot(in_plane, l.z()) - ring.tube_radius_m;
}

double rayRing(const EllipticRing& ring, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
               double max_range) {
  // The tube lies inside its bounding sphere and inside the slab |w| <= tube radius around its
  // plane: sphere-trace only where the ray is in both (a short stretch for most rays).
  const Eigen::Vector3d oc = origin - ring.center;
  const double r = ring.boundingRadius();
  const double b = oc.dot(dir), c = oc.squaredNorm() - r * r;
  const double disc = b * b - c;
  if (disc < 0.0) return -1.0;
  const double root = std::sqrt(disc);
  double t_lo = std::max(0.0, -b - root), t_hi = std::min(max_range, -b + root);
  const double cy = std::cos(ring.yaw), sy = std::sin(ring.yaw);
  const double w0 = cy * oc.x() + sy * oc.y(), dw = cy * dir.x() + sy * dir.y();
  const double half = ring.tube_radius_m + kSurfaceTolerance;
  if (std::abs(dw) < 1e-12) {
    if (std::abs(w0) > half) return -1.0;
  } else {
    double ta = (-half - w0) / dw, tb = (half - w0) / dw;
    if (ta > tb) std::swap(ta, tb);
    t_lo = std::max(t_lo, ta);
    t_hi = std::min(t_hi, tb);
  }
  if (t_lo > t_hi) return -1.0;
  double t = t_lo;
  for (int i = 0; i < kMaxSteps && t <= t_hi; ++i) {
    const double d = distanceToRing(ring, origin + t * dir);
    if (d < kSurfaceTolerance) return t;
    t += d;
  }
  return -1.0;
}

}  // namespace mmh::sim
