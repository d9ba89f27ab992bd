#include "mmh/eam/collision_pairs.hpp"

#include "mmh/common/collision_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace mmh::eam {
namespace {

constexpr int kMaxPairsPerPoint = 8;
constexpr double kMaxClearance = 0.5;  // m, upper bound when a pair's clearance is raised

// Clearance a pair at p facing v can ask for: half the free width beyond p along v (so that the
// pairs of the two walls of a tight passage agree on its middle), at most `limit`.
double maxClearance(const VoxelGrid& grid, const Eigen::Vector3d& p, const Eigen::Vector3d& v,
                    double limit) {
  const double step = 0.5 * grid.resolution();
  for (double w = step; w <= 2.0 * limit + 1e-9; w += step) {
    if (grid.isBlockedPoint(p + w * v)) return 0.5 * (w - step);
  }
  return limit;
}

// Cubic coefficients (columns, ascending powers of local time) of knot interval i.
Eigen::Matrix<double, 3, 4> segmentCoeffs(const Eigen::Matrix3Xd& q, int i, double dt) {
  const Eigen::Vector3d q0 = q.col(i), q1 = q.col(i + 1), q2 = q.col(i + 2), q3 = q.col(i + 3);
  Eigen::Matrix<double, 3, 4> c;
  c.col(0) = (q0 + 4.0 * q1 + q2) / 6.0;
  c.col(1) = (q2 - q0) / (2.0 * dt);
  c.col(2) = (q0 - 2.0 * q1 + q2) / (2.0 * dt * dt);
  c.col(3) = (-q0 + 3.0 * q1 - 3.0 * q2 + q3) / (6.0 * dt * dt * dt);
  return c;
}

// Weights of Q_i .. Q_{i+3} at local parameter s in [0, 1].
Eigen::Vector4d basisWeights(double s) {
  const double s2 = s * s, s3 = s2 * s;
  return Eigen::Vector4d((1.0 - s) * (1.0 - s) * (1.0 - s), 3.0 * s3 - 6.0 * s2 + 4.0,
                         -3.0 * s3 + 3.0 * s2 + 3.0 * s + 1.0, s3) /
         6.0;
}

// Point of the polyline where it crosses the plane through x with normal n, nearest to x; the
// nearest vertex when the polyline does not cross it.
Eigen::Vector3d planeCrossing(const std::vector<Eigen::Vector3d>& path, const Eigen::Vector3d& x,
                              const Eigen::Vector3d& n) {
  bool found = false;
  Eigen::Vector3d best = path.front();
  double best_d = std::numeric_limits<double>::infinity();
  auto consider = [&](const Eigen::Vector3d& c) {
    const double d = (c - x).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  };
  for (size_t k = 0; k + 1 < path.size(); ++k) {
    const double s0 = (path[k] - x).dot(n), s1 = (path[k + 1] - x).dot(n);
    if (s0 == 0.0) {
      consider(path[k]);
      found = true;
    } else if ((s0 < 0.0) != (s1 < 0.0) && s1 != 0.0) {
      consider(path[k] + (path[k + 1] - path[k]) * (s0 / (s0 - s1)));
      found = true;
    }
  }
  if (!found) {
    for (const auto& c : path) consider(c);
  }
  return best;
}

// Unit direction away from the occupied cells around x (within the inflation radius and a
// voxel), orthogonal to the travel direction t: the sum of the unit vectors from those cells to
// x, weighted more the nearer they are (a local stand-in for a distance-field gradient; cells
// above and below cancel, so a vertical pillar pushes sideways). False when there are none, or
// when the push is mostly along t (entering an obstacle head-on: no side is preferred).
bool awayFromObstacle(const VoxelGrid& grid, const Eigen::Vector3d& x, const Eigen::Vector3d& t,
                      Eigen::Vector3d* away) {
  const double res = grid.resolution();
  const double reach = grid.inflationRadius() + res;
  const int r = static_cast<int>(std::ceil(reach / res));
  const Eigen::Vector3i c = grid.localIndexOf(x);
  const Eigen::Vector3i& size = grid.size();
  // Offset of x from its cell's centre; the offset from a neighbour's centre follows by adding
  // whole voxels. Rows along x are contiguous in memory.
  const Eigen::Vector3d x_local = x - grid.centerOfLocal(c);
  const int x_lo = std::max(0, c.x() - r), x_hi = std::min(size.x() - 1, c.x() + r);
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (int z = std::max(0, c.z() - r); z <= std::min(size.z() - 1, c.z() + r); ++z) {
    for (int y = std::max(0, c.y() - r); y <= std::min(size.y() - 1, c.y() + r); ++y) {
      const int64_t row = grid.linearIndex(Eigen::Vector3i(0, y, z));
      for (int xi = x_lo; xi <= x_hi; ++xi) {
        if (grid.atLinear(row + xi) != Occupancy::kOccupied) continue;
        const Eigen::Vector3d diff =
            x_local - res * Eigen::Vector3d(xi - c.x(), y - c.y(), z - c.z());
        const double d = diff.norm();
        if (d >= reach || d < 1e-9) continue;
        n += diff / d * (reach - d) * (reach - d);
      }
    }
  }
  const double total = n.norm();
  if (total < 1e-12) return false;
  const Eigen::Vector3d side = n - n.dot(t) * t;
  if (side.norm() < 0.25 * total) return false;
  *away = side.normalized();
  return true;
}

}  // namespace

std::vector<CollisionStretch> findCollisionStretches(const UniformBspline& spline,
                                                     const VoxelGrid& grid, double escape_radius_m,
                                                     double step_m, double escape_min_distance_m,
                                                     double forced_until_s) {
  std::vector<CollisionStretch> out;
  const Eigen::Matrix3Xd& q = spline.controlPoints();
  const double dt = spline.knotSpan();
  const double step = step_m;
  const Eigen::Vector3d start = spline.evaluate(0, 0.0);
  bool escaping = true;  // still in the leading part that may leave the inflated margin
  bool in_run = false;
  CollisionStretch run;
  Eigen::Vector3d last_free = start;
  double last_free_t = 0.0;
  bool have_free = false;
  const int segments = spline.numSegments();
  for (int i = 0; i < segments; ++i) {
    const Eigen::Matrix<double, 3, 4> c = segmentCoeffs(q, i, dt);
    // Arc length bound: the length of the interval's Bezier control polygon (P0..P3 from
    // Q_i..Q_{i+3}), which the curve never exceeds.
    const Eigen::Vector3d p0 = (q.col(i) + 4.0 * q.col(i + 1) + q.col(i + 2)) / 6.0;
    const Eigen::Vector3d p1 = (2.0 * q.col(i + 1) + q.col(i + 2)) / 3.0;
    const Eigen::Vector3d p2 = (q.col(i + 1) + 2.0 * q.col(i + 2)) / 3.0;
    const Eigen::Vector3d p3 = (q.col(i + 1) + 4.0 * q.col(i + 2) + q.col(i + 3)) / 6.0;
    const double length = (p1 - p0).norm() + (p2 - p1).norm() + (p3 - p2).norm();
    const int n = std::max(1, static_cast<int>(std::ceil(length / step)));
    const int last = (i + 1 == segments) ? n : n - 1;  // the end point only once, at the end
    for (int k = 0; k <= last; ++k) {
      const double s = static_cast<double>(k) / n;
      const double tl = s * dt;
      CurveSample sample;
      sample.t = i * dt + tl;
      sample.segment = i;
      sample.s = s;
      sample.point = c.col(0) + tl * (c.col(1) + tl * (c.col(2) + tl * c.col(3)));
      const Eigen::Vector3i cell = grid.localIndexOf(sample.point);
      const bool in_window = grid.inWindow(cell);
      const int64_t idx = in_window ? grid.linearIndex(cell) : 0;
      bool blocked = in_window && grid.isBlockedLinear(idx);
      if (escaping) {
        if (blocked && grid.atLinear(idx) != Occupancy::kOccupied &&
            (sample.point - start).norm() <= escape_radius_m &&
            keepsEscapeDistance(grid, sample.point, escape_min_distance_m)) {
          blocked = false;  // leaving the margin the start is in
        } else {
          escaping = false;
        }
      }
      if (blocked && grid.atLinear(idx) != Occupancy::kOccupied &&
          forcedByStart(grid, sample.point, sample.t, forced_until_s, escape_min_distance_m)) {
        blocked = false;
      }
      if (blocked) {
        if (!in_run) {
          run = CollisionStretch();
          run.from_start = !have_free;
          run.before = have_free ? last_free : start;
          run.t_before = have_free ? last_free_t : 0.0;
          in_run = true;
        }
        // Only blocked samples keep their velocity (the anchor pairs' travel direction).
        sample.velocity = c.col(1) + tl * (2.0 * c.col(2) + tl * 3.0 * c.col(3));
        run.blocked.push_back(sample);
      } else {
        if (in_run) {
          run.after = sample.point;
          run.t_after = sample.t;
          out.push_back(std::move(run));
          in_run = false;
        }
        last_free = sample.point;
        last_free_t = sample.t;
        have_free = true;
      }
    }
  }
  if (in_run) {
    run.after = spline.evaluate(0, spline.duration());  // blocked target: the caller rejects it
    run.t_after = spline.duration();
    out.push_back(std::move(run));
  }
  return out;
}

int addAnchorPairs(const CollisionStretch& stretch, const std::vector<Eigen::Vector3d>& guide_path,
                   const UniformBspline& spline, const VoxelGrid& grid, int first_free,
                   int last_free, double clearance_m, PairSet& pairs) {
  if (guide_path.size() < 2 || stretch.blocked.empty()) return 0;
  const Eigen::Matrix3Xd& q = spline.controlPoints();
  if (static_cast<int>(pairs.size()) < q.cols()) pairs.resize(q.cols());
  // For each control point, the blocked sample it weighs most on (weight >= 0.1).
  struct Probe {
    double weight = 0.0;
    const CurveSample* sample = nullptr;
  };
  std::map<int, Probe> probes;
  for (const CurveSample& s : stretch.blocked) {
    const Eigen::Vector4d w = basisWeights(s.s);
    for (int k = 0; k < 4; ++k) {
      const int i = s.segment + k;
      if (i < first_free || i > last_free || w[k] < 0.1) continue;
      Probe& p = probes[i];
      if (w[k] > p.weight) p = Probe{w[k], &s};
    }
  }
  const double res = grid.resolution();
  int added = 0;
  for (const auto& [i, probe] : probes) {
    Eigen::Vector3d x, tangent;
    if (grid.isBlockedPoint(q.col(i))) {
      x = q.col(i);  // EGO-Planner's case: the control point itself is in the obstacle
      tangent = q.col(i + 1) - q.col(i - 1);
    } else {
      x = probe.sample->point;
      tangent = probe.sample->velocity;
      if (tangent.norm() < 1e-6) tangent = q.col(i + 1) - q.col(i - 1);
    }
    if (tangent.norm() < 1e-9) continue;
    tangent.normalize();
    Eigen::Vector3d g = planeCrossing(guide_path, x, tangent);
    Eigen::Vector3d v = g - x;
    double len = v.norm();
    v /= std::max(len, 1e-12);
    if (len < res) {
      // The guide crosses the plane within a voxel of x (typically where the curve only grazes
      // the margin, or enters or leaves the obstacle next to the guide's end points): that
      // direction is noise. A point in the margin is pushed straight away from the obstacle
      // it grazes instead; a point in an occupied cell gets no pair from this probe.
      Eigen::Vector3d away;
      if (grid.isOccupiedPoint(x) || !awayFromObstacle(grid, x, tangent, &away)) continue;
      v = away;
      len = 0.0;
      for (double w = 0.5 * res; w <= grid.inflationRadius() + 2.0 * res; w += 0.5 * res) {
        if (!grid.isBlockedPoint(x + w * v)) {
          len = w;
          break;
        }
      }
      if (len <= 0.0) continue;
      g = x + len * v;
    }
    // From the free guide point towards x: the last free point is the obstacle surface.
    Eigen::Vector3d p = x;
    const int steps = static_cast<int>(std::ceil(len / (0.5 * res)));
    Eigen::Vector3d prev = g;
    for (int k = 0; k <= steps; ++k) {
      const Eigen::Vector3d y = g - v * std::min(len, k * 0.5 * res);
      if (grid.isBlockedPoint(y)) {
        p = prev;
        break;
      }
      prev = y;
    }
    auto& list = pairs[i];
    AnchorPair* similar = nullptr;
    for (AnchorPair& old : list) {
      if (old.v.dot(v) > 0.866 && std::abs((p - old.p).dot(old.v)) < res) {
        similar = &old;
        break;
      }
    }
    if (similar) {
      // The same obstacle face again: its pair is there, yet the curve still hits. If the
      // control point already keeps the pair's clearance, the plane approximates the (round,
      // voxelised) obstacle too loosely here: ask for more room, within the free width.
      const double d = (q.col(i) - similar->p).dot(similar->v);
      if (d >= similar->clearance - 0.25 * res) {
        const double wider = std::min(similar->clearance + 0.5 * res,
                                      maxClearance(grid, similar->p, similar->v, kMaxClearance));
        if (wider > similar->clearance + 1e-9) {
          similar->clearance = wider;
          ++added;
        }
      }
      continue;
    }
    if (static_cast<int>(list.size()) >= kMaxPairsPerPoint) continue;
    list.push_back(AnchorPair{p, v, std::min(clearance_m, maxClearance(grid, p, v, clearance_m))});
    ++added;
  }
  return added;
}

}  // namespace mmh::eam
