// FIRI-style inflation of one convex polytope around a seed segment (after Wang et al., T-RO
// 2022): alternate (1) a greedy set of separating hyperplanes, each through the obstacle point
// nearest in the metric of the current ellipsoid and as far from the ellipsoid centre as the
// seed allows, until no obstacle point is left inside, with (2) the maximum-volume ellipsoid
// inscribed in the result, which re-centres and re-shapes the metric for the next round.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mmh/som/ellipsoid.hpp"
#include "mmh/som/polytope.hpp"

namespace mmh::som {

struct InflationOptions {
  int iterations = 2;  // hyperplane rounds; an ellipsoid step runs between two rounds
  InscribedEllipsoidOptions ellipsoid;
  double plane_offset_m = 1e-6;  // every excluded point ends up this far outside its face
  // > 0: rounds before the last use only the points (and the box) within this distance of the
  // seed's bounding box; they only shape the ellipsoid for the last round.
  double early_round_margin_m = 0.0;
};

// The seed of a polytope: one to three points whose convex hull (a point, a segment, a
// triangle) must stay inside it.
using Seed = std::vector<Eigen::Vector3d>;

// The hyperplane through x (in the ellipsoid's unit-ball coordinates) that keeps the seed points
// on the origin's side and is farthest from the origin: y with y . x = 1, y . s_i <= 1 - m and
// |y| minimal (a 3-variable QP solved by enumerating its active sets); the face is
// {u : y . u <= 1}. False if no such plane exists (x in the seed's hull).
bool separatingPlane(const Eigen::Vector3d& x, const Eigen::Vector3d* seed, int count,
                     Eigen::Vector3d* y, double seed_margin = 0.0);
bool separatingPlane(const Eigen::Vector3d& x, const Eigen::Vector3d& ua, const Eigen::Vector3d& ub,
                     Eigen::Vector3d* y, double seed_margin = 0.0);

class PolytopeInflator {
 public:
  // Polytope inside the box [lo, hi] that contains the seed and excludes every point of
  // `points` (strictly). The seed must lie in the box. False if some point lies in the seed's
  // hull. `ellipsoid` receives the metric of the last hyperplane round.
  bool inflate(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& lo,
               const Eigen::Vector3d& hi, const Seed& seed, const InflationOptions& options,
               Polytope* poly, Ellipsoid* ellipsoid);

  // One hyperplane round: adds faces to `poly` until it excludes every point of `points`.
  bool exclude(const std::vector<Eigen::Vector3d>& points, const Ellipsoid& metric,
               const Seed& seed, double offset, Polytope* poly);

 private:
  std::vector<double> xs_, ys_, zs_, dist2_;
  std::vector<Eigen::Vector3d> inner_points_;
};

}  // namespace mmh::som
