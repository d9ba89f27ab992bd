#include "mmh/som/polytope_inflation.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

namespace mmh::som {

namespace {
// Room kept on both sides of a face, relative, in the ellipsoid's unit-ball coordinates.
constexpr double kSeedMargin = 1e-3;
constexpr double kBoxInset = 1e-6;  // m
}  // namespace

bool separatingPlane(const Eigen::Vector3d& x, const Eigen::Vector3d* seed, int count,
                     Eigen::Vector3d* y, double seed_margin) {
  // The optimum is the minimum-norm point of the affine set of one of the active sets (no seed
  // constraint, one, or two of them: with y . x = 1 that is at most three equations in R^3);
  // every candidate has |y| >= the optimum, so the smallest feasible one wins.
  const double xx = x.squaredNorm();
  if (!(xx > 0.0) || count < 1 || count > 3) return false;
  const double tol = 1e-9, side = 1.0 - seed_margin;
  double best = std::numeric_limits<double>::infinity();
  auto consider = [&](const Eigen::Vector3d& cand) {
    if (!cand.allFinite()) return;
    for (int i = 0; i < count; ++i)
      if (cand.dot(seed[i]) > side + tol) return;
    const double n = cand.squaredNorm();
    if (n < best) {
      best = n;
      *y = cand;
    }
  };
  consider(x / xx);
  for (int i = 0; i < count; ++i) {
    // min |y| with y . x = 1, y . v = side: y = G^T (G G^T)^-1 (1, side).
    const Eigen::Vector3d& v = seed[i];
    const double xv = x.dot(v), vv = v.squaredNorm();
    const double det = xx * vv - xv * xv;
    if (det <= 1e-12 * xx * vv) continue;
    consider((vv - xv * side) / det * x + (xx * side - xv) / det * v);
  }
  for (int i = 0; i < count; ++i) {
    for (int j = i + 1; j < count; ++j) {
      Eigen::Matrix3d g;
      g.row(0) = x.transpose();
      g.row(1) = seed[i].transpose();
      g.row(2) = seed[j].transpose();
      const double det = g.determinant();
      const double scale = std::sqrt(xx * seed[i].squaredNorm() * seed[j].squaredNorm());
      if (std::abs(det) > 1e-10 * scale) consider(g.inverse() * Eigen::Vector3d(1.0, side, side));
    }
  }
  return std::isfinite(best);
}

bool separatingPlane(const Eigen::Vector3d& x, const Eigen::Vector3d& ua, const Eigen::Vector3d& ub,
                     Eigen::Vector3d* y, double seed_margin) {
  const Eigen::Vector3d seed[2] = {ua, ub};
  return separatingPlane(x, seed, 2, y, seed_margin);
}

bool PolytopeInflator::exclude(const std::vector<Eigen::Vector3d>& points, const Ellipsoid& metric,
                               const Seed& seed, double offset, Polytope* poly) {
  if (seed.empty() || seed.size() > 3) return false;
  const Eigen::Matrix3d cinv = metric.shape.inverse();
  const Eigen::Vector3d& d = metric.center;
  const int k = static_cast<int>(seed.size());
  Eigen::Vector3d su[3];
  for (int i = 0; i < k; ++i) su[i] = cinv * (seed[i] - d);
  // Structure of arrays, compacted as faces cut points away: the scans stay contiguous.
  const int n = static_cast<int>(points.size());
  xs_.resize(n);
  ys_.resize(n);
  zs_.resize(n);
  dist2_.resize(n);
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector3d& p = points[j];
    xs_[j] = p.x();
    ys_[j] = p.y();
    zs_[j] = p.z();
    dist2_[j] = (cinv * (p - d)).squaredNorm();
  }
  int count = n;
  while (count > 0) {
    int best = 0;
    for (int i = 1; i < count; ++i)
      if (dist2_[i] < dist2_[best]) best = i;
    const Eigen::Vector3d p(xs_[best], ys_[best], zs_[best]);
    // Prefer a face with a little room on both sides (the seed strictly inside, the point
    // strictly outside); a point very close to the seed leaves only the face through it.
    const Eigen::Vector3d xp = cinv * (p - d);
    Eigen::Vector3d y;
    double level = 1.0 - 0.5 * kSeedMargin, shift = 0.0;
    if (!separatingPlane(xp, su, k, &y, kSeedMargin)) {
      if (!separatingPlane(xp, su, k, &y, 0.0)) return false;
      level = 1.0;
      shift = offset;
    }
    // {u : y . u <= level} with u = C^-1 (x - d) is {x : n . x <= level + n . d}, n = C^-1 y.
    const Eigen::Vector3d normal = cinv * y;
    const double norm = normal.norm();
    const Eigen::Vector3d unit = normal / norm;
    const double rhs = (level + normal.dot(d)) / norm - shift;
    if (!poly->addHalfspace(unit, rhs)) return false;
    const double nx = unit.x(), ny = unit.y(), nz = unit.z();
    int kept = 0;
    for (int i = 0; i < count; ++i) {
      if (nx * xs_[i] + ny * ys_[i] + nz * zs_[i] < rhs) {
        xs_[kept] = xs_[i];
        ys_[kept] = ys_[i];
        zs_[kept] = zs_[i];
        dist2_[kept] = dist2_[i];
        ++kept;
      }
    }
    if (kept >= count) return false;  // cannot happen: the chosen point is cut (guard)
    count = kept;
  }
  return true;
}

bool PolytopeInflator::inflate(const std::vector<Eigen::Vector3d>& points,
                               const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                               const Seed& seed, const InflationOptions& options, Polytope* poly,
                               Ellipsoid* ellipsoid) {
  if (seed.empty() || seed.size() > 3) return false;
  // First metric: an ellipsoid stretched along the seed's longest edge, centred on the seed,
  // whose cross-section reaches the nearest obstacle point, so that the first faces come from
  // the obstacles beside the seed.
  Eigen::Vector3d a = seed.front(), b = seed.front(), center = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < seed.size(); ++i) {
    center += seed[i] / static_cast<double>(seed.size());
    for (size_t j = i + 1; j < seed.size(); ++j)
      if ((seed[i] - seed[j]).squaredNorm() > (a - b).squaredNorm()) {
        a = seed[i];
        b = seed[j];
      }
  }
  const Eigen::Vector3d ab = b - a;
  const double len = ab.norm();
  double nearest2 = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : points) {
    const double t = len > 0.0 ? std::clamp((p - a).dot(ab) / (len * len), 0.0, 1.0) : 0.0;
    nearest2 = std::min(nearest2, (a + t * ab - p).squaredNorm());
  }
  const double r = std::clamp(std::sqrt(nearest2), 0.05, 1.0);
  Ellipsoid metric;
  metric.center = center;
  metric.shape = r * Eigen::Matrix3d::Identity();
  if (len > 0.0) {
    const Eigen::Vector3d e = ab / len;
    metric.shape += (std::max(0.5 * len, r) - r) * e * e.transpose();
  }
  // The rounds before the last only shape the metric: they may look at a smaller box around
  // the seed (fewer points, fewer faces for the ellipsoid step).
  Eigen::Vector3d seed_lo = seed.front(), seed_hi = seed.front();
  for (const Eigen::Vector3d& p : seed) {
    seed_lo = seed_lo.cwiseMin(p);
    seed_hi = seed_hi.cwiseMax(p);
  }
  const Eigen::Vector3d inner_lo = (seed_lo.array() - options.early_round_margin_m).max(lo.array());
  const Eigen::Vector3d inner_hi = (seed_hi.array() + options.early_round_margin_m).min(hi.array());
  const bool shrink_early = options.early_round_margin_m > 0.0;
  if (shrink_early && options.iterations > 1) {
    inner_points_.clear();
    for (const Eigen::Vector3d& p : points)
      if ((p.array() >= inner_lo.array()).all() && (p.array() <= inner_hi.array()).all())
        inner_points_.push_back(p);
  }
  for (int round = 0; round < options.iterations; ++round) {
    const bool last = round + 1 == options.iterations;
    const bool inner = shrink_early && !last;
    Polytope candidate;
    // A hair inside the box, so that cell centres on its faces are strictly outside.
    candidate.addBox((inner ? inner_lo : lo).array() + kBoxInset,
                     (inner ? inner_hi : hi).array() - kBoxInset);
    if (!exclude(inner ? inner_points_ : points, metric, seed, options.plane_offset_m, &candidate))
      return false;
    *poly = std::move(candidate);
    *ellipsoid = metric;
    if (round + 1 == options.iterations) break;
    Ellipsoid next;
    if (!inscribedEllipsoid(*poly, metric, &next, options.ellipsoid)) break;
    if (round > 0 && next.volume() <= metric.volume() * (1.0 + 1e-3)) break;  // converged
    metric = next;
  }
  return true;
}

}  // namespace mmh::som
