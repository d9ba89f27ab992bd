#include "mmh/som/corridor.hpp"

#include <algorithm>
#include <cmath>

#include "mmh/common/vehicle_limits.hpp"

namespace mmh::som {

PathCurve::PathCurve(const std::vector<Eigen::Vector3d>& points) {
  for (const Eigen::Vector3d& p : points) {
    if (!points_.empty() && (p - points_.back()).norm() < 1e-9) continue;  // no empty segments
    points_.push_back(p);
  }
  if (points_.size() == 1) points_.push_back(points_.front());
  cumulative_.assign(1, 0.0);
  for (size_t i = 1; i < points_.size(); ++i)
    cumulative_.push_back(cumulative_.back() + (points_[i] - points_[i - 1]).norm());
}

int PathCurve::segmentAt(double s) const {
  const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
  const int k = static_cast<int>(it - cumulative_.begin()) - 1;
  return std::clamp(k, 0, numSegments() - 1);
}

Eigen::Vector3d PathCurve::pointAt(double s) const {
  const int k = segmentAt(s);
  const double len = cumulative_[k + 1] - cumulative_[k];
  const double t = len > 0.0 ? std::clamp((s - cumulative_[k]) / len, 0.0, 1.0) : 0.0;
  return points_[k] + t * (points_[k + 1] - points_[k]);
}

double PathCurve::segmentEndAfter(double s) const {
  int k = segmentAt(s);
  if (segmentEnd(k) <= s + 1e-9 && k + 1 < numSegments()) ++k;
  return segmentEnd(k);
}

namespace {

// Arc length at which the path, followed from `from` (inside `poly`), leaves `poly`: exact per
// segment, since a segment meets a convex polytope in one interval.
double exitArcLength(const PathCurve& path, const Polytope& poly, double from) {
  const Polytope::Matrix& h = poly.halfspaces();
  for (int k = path.segmentAt(from); k < path.numSegments(); ++k) {
    const double s0 = std::max(from, path.segmentStart(k)), s1 = path.segmentEnd(k);
    if (s1 <= s0) continue;
    const Eigen::Vector3d p = path.pointAt(s0), dir = (path.pointAt(s1) - p) / (s1 - s0);
    double t_hi = s1 - s0;
    for (int i = 0; i < h.rows(); ++i) {
      const double c = h.row(i).head<3>().dot(dir);
      const double slack = h(i, 3) - h.row(i).head<3>().dot(p);
      if (c > 1e-12) t_hi = std::min(t_hi, slack / c);
    }
    if (t_hi < s1 - s0) return s0 + std::max(0.0, t_hi);
  }
  return path.length();
}

}  // namespace

namespace {

// Straight segment free of blocked cells (samples a quarter voxel apart); cells of the escape
// zone count as free.
bool segmentVisible(const VoxelGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                    const EscapeZone& escape) {
  const int n =
      std::max(1, static_cast<int>(std::ceil((b - a).norm() / (0.25 * grid.resolution()))));
  const double r2 = escape.radius * escape.radius;
  for (int i = 0; i <= n; ++i) {
    const Eigen::Vector3d p = a + (b - a) * (static_cast<double>(i) / n);
    const Eigen::Vector3i c = grid.localIndexOf(p);
    if (!grid.isBlocked(c)) continue;
    if (escape.radius > 0.0 && (grid.centerOfLocal(c) - escape.center).squaredNorm() <= r2 &&
        escape.frees(grid, c, grid.centerOfLocal(c)))
      continue;
    return false;
  }
  return true;
}

// A point inside `poly` at least `margin` from its faces, found on the segment from `p` towards
// `center` (the nearest such point to p); the best point of the segment if none is that deep.
Eigen::Vector3d pullInside(const Polytope& poly, const Eigen::Vector3d& p,
                           const Eigen::Vector3d& center, double margin) {
  Eigen::Vector3d best = p;
  double best_slack = -poly.maxViolation(p);
  for (int i = 1; i <= 16 && best_slack < margin; ++i) {
    const Eigen::Vector3d q = p + (center - p) * (i / 16.0);
    const double slack = -poly.maxViolation(q);
    if (slack > best_slack) {
      best_slack = slack;
      best = q;
    }
  }
  return best;
}

// Free triangle: segments from `c` to points along [a, b] at most half a voxel apart.
bool triangleVisible(const VoxelGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                     const Eigen::Vector3d& c, const EscapeZone& escape) {
  const int n =
      std::max(1, static_cast<int>(std::ceil((b - a).norm() / (0.5 * grid.resolution()))));
  for (int i = 0; i <= n; ++i)
    if (!segmentVisible(grid, c, a + (b - a) * (static_cast<double>(i) / n), escape)) return false;
  return true;
}

// Where a vehicle at p moving at v stops when braking at a_max, pulled back along the way until
// the straight line to it is free; p itself if it is (nearly) at rest.
Eigen::Vector3d stoppingPoint(const VoxelGrid& grid, const Eigen::Vector3d& p,
                              const Eigen::Vector3d& v, double a_max, const EscapeZone& escape) {
  const double speed = v.norm();
  if (speed < 0.3 || a_max <= 0.0) return p;
  const Eigen::Vector3d dir = v / speed;
  for (double d = stoppingDistance(speed, a_max); d > 0.1; d -= grid.resolution()) {
    if (segmentVisible(grid, p, p + d * dir, escape)) return p + d * dir;
  }
  return p;
}

}  // namespace

bool CorridorBuilder::build(const VoxelGrid& grid, const std::vector<Eigen::Vector3d>& raw_path,
                            const Eigen::Vector3d& bound_lo, const Eigen::Vector3d& bound_hi,
                            const EscapeZone& escape, const CorridorParams& params, Corridor* out,
                            std::string* why, const Eigen::Vector3d& start_velocity,
                            double max_acc_mps2) {
  *out = Corridor();
  out->bound_lo = bound_lo;
  out->bound_hi = bound_hi;
  if (raw_path.empty()) {
    *why = "empty path";
    return false;
  }
  const PathCurve path(raw_path);
  const Eigen::Vector3d target = raw_path.back();
  InflationOptions inflation;
  inflation.iterations = params.iterations;
  inflation.early_round_margin_m = params.early_round_margin_m;
  const double step = grid.resolution();

  std::vector<Polytope> polys;
  std::vector<Eigen::Vector3d> junctions;
  std::vector<Ellipsoid> ellipsoids;
  // Seed i runs from `a` (the start, then the junction with the previous polytope) to the
  // farthest point of the path ahead of `progress` that is visible from `a`.
  Eigen::Vector3d a = path.pointAt(0.0);
  double progress = 0.0;
  while (true) {
    if (static_cast<int>(polys.size()) >= params.max_polytopes) {
      *why = "more than " + std::to_string(params.max_polytopes) + " polytopes needed";
      return false;
    }
    double seed_s = -1.0;
    const double far = std::min(path.length(), progress + params.seed_length_m);
    for (double s = far; s > progress + 1e-9; s -= step) {
      if ((path.pointAt(s) - a).norm() <= params.seed_length_m &&
          segmentVisible(grid, a, path.pointAt(s), escape)) {
        seed_s = s;
        break;
      }
    }
    if (seed_s < 0.0) {
      // Nothing ahead is visible from the pulled-in junction: put the junction back on the
      // path (it is inside the previous polytope) and seed along the current path segment,
      // which is free.
      a = path.pointAt(progress);
      if (!junctions.empty()) junctions.back() = a;
      // Along the segment that leads on from `progress` (a seed that ended a hair short of a
      // vertex left `progress` there; the segment ending at the vertex gave no seed and the
      // corridor "made no progress", a som flight stuck at 0.2 obs/m^2).
      seed_s = std::min(progress + params.seed_length_m, path.segmentEndAfter(progress));
      if (seed_s <= progress + 1e-9) {
        *why = "the corridor makes no progress along the path";
        return false;
      }
    }
    Eigen::Vector3d b = path.pointAt(seed_s);
    Seed seed{a, b};
    if (polys.empty()) {
      // A moving start: the first polytope also covers the way to where the vehicle would stop
      // when braking, so that the trajectory can turn without leaving the corridor.
      const Eigen::Vector3d q = stoppingPoint(grid, a, start_velocity, max_acc_mps2, escape);
      if ((q - a).norm() > 0.1) {
        // The triangle start - seed end - stopping point must be free; shorten the seed if not.
        for (double t : {1.0, 0.5, 0.25}) {
          const Eigen::Vector3d bt = a + t * (b - a);
          if ((q - bt).norm() > 0.1 && triangleVisible(grid, a, bt, q, escape)) {
            seed = {a, bt, q};
            seed_s = progress + t * (seed_s - progress);  // a is the start, on the path
            break;
          }
        }
      }
    }
    Eigen::Vector3d seed_lo = a.cwiseMin(b), seed_hi = a.cwiseMax(b);
    for (const Eigen::Vector3d& p : seed) {
      seed_lo = seed_lo.cwiseMin(p);
      seed_hi = seed_hi.cwiseMax(p);
    }
    const Eigen::Vector3d margin(params.box_margin_m, params.box_margin_m, params.box_margin_z_m);
    const Eigen::Vector3d box_lo = (seed_lo - margin).cwiseMax(bound_lo);
    const Eigen::Vector3d box_hi = (seed_hi + margin).cwiseMin(bound_hi);
    if ((box_hi - box_lo).minCoeff() <= 0.0) {
      *why = "seed outside the corridor bounds";
      return false;
    }
    mask_.build(grid, box_lo, box_hi, escape, params.check_inflation_m,
                params.check_face_clearance_m, params.check_whole_cells);
    mask_.surfacePoints(&points_);
    out->surface_points += static_cast<int>(points_.size());
    Polytope poly;
    Ellipsoid metric;
    if (!inflator_.inflate(points_, box_lo, box_hi, seed, inflation, &poly, &metric)) {
      *why = "an obstacle point lies on the seed segment";
      return false;
    }
    // Surface points suffice in practice; this scan proves it for every blocked cell centre.
    bool clean = false;
    for (int pass = 0; pass < 4 && !clean; ++pass) {
      mask_.pointsInside(poly, &extra_);
      clean = extra_.empty();
      if (!clean && !inflator_.exclude(extra_, metric, seed, inflation.plane_offset_m, &poly)) {
        *why = "an obstacle point lies on the seed segment";
        return false;
      }
    }
    if (!clean) {
      *why = "could not exclude every blocked cell";
      return false;
    }
    polys.push_back(std::move(poly));
    ellipsoids.push_back(metric);
    const Polytope& p = polys.back();
    // The target ends the corridor once it lies the junction margin inside. A target that is
    // only in the box grown round a seed short of it may sit on a face, which the optimiser
    // (aiming inside every face, with the end point fixed) cannot satisfy: one more polytope
    // seeded up to the target. Only a seed that ends at the target may leave it on a face.
    const bool seed_ends_at_target = seed_s >= path.length() - 1e-9;
    if (p.contains(target, params.junction_margin_m) ||
        (seed_ends_at_target && p.contains(target, -kCorridorContainTolerance)))
      break;

    // Junction: where the path leaves this polytope, pulled inside by the junction margin.
    const double exit = std::max(seed_s, exitArcLength(path, p, seed_s));
    if (exit <= progress + 1e-6) {
      *why = "the corridor makes no progress along the path";
      return false;
    }
    double back = std::max(seed_s, exit - params.overlap_backoff_m);
    if (back < progress + 0.25 * (exit - progress)) back = progress + 0.5 * (exit - progress);
    a = pullInside(p, path.pointAt(back), metric.center, params.junction_margin_m);
    junctions.push_back(a);
    progress = back;
  }
  out->polytopes_built = static_cast<int>(polys.size());

  // Remove polytope i when its neighbours overlap (by the junction margin) somewhere on the
  // segment between its two junctions, which lies inside it.
  for (size_t i = 1; i + 1 < polys.size();) {
    bool dropped = false;
    for (int k = 0; k <= 8 && !dropped; ++k) {
      const Eigen::Vector3d q = junctions[i - 1] + (junctions[i] - junctions[i - 1]) * (k / 8.0);
      if (polys[i - 1].contains(q, params.junction_margin_m) &&
          polys[i + 1].contains(q, params.junction_margin_m)) {
        polys.erase(polys.begin() + i);
        ellipsoids.erase(ellipsoids.begin() + i);
        junctions.erase(junctions.begin() + i);
        junctions[i - 1] = q;
        dropped = true;
      }
    }
    if (!dropped) ++i;
  }
  out->polytopes = std::move(polys);
  out->junctions = std::move(junctions);
  out->ellipsoids = std::move(ellipsoids);
  return true;
}

}  // namespace mmh::som
