// Ellipsoids {C u + d : |u| <= 1} and the (approximately) maximum-volume ellipsoid inscribed in
// a polytope: the ellipsoid step of the FIRI-style corridor inflation.
#pragma once

#include <Eigen/Core>

#include "mmh/som/polytope.hpp"

namespace mmh::som {

struct Ellipsoid {
  Eigen::Matrix3d shape = Eigen::Matrix3d::Identity();  // C, symmetric positive definite
  Eigen::Vector3d center = Eigen::Vector3d::Zero();     // d

  double volume() const;  // 4/3 pi det C
  bool contains(const Eigen::Vector3d& p) const;
  // Largest value of a . x over the ellipsoid: a . d + |C a|.
  double support(const Eigen::Vector3d& a) const;
};

struct InscribedEllipsoidOptions {
  // Log-barrier weights mu, from the first to the last stage (each stage divides by 10). The
  // result's log det is within about (number of faces) x mu_final of the true maximum.
  double barrier_start = 1e-2;
  double barrier_final = 1e-2;  // a ~90 % ellipsoid is plenty for the metric of the next round
  int max_newton_steps = 6;     // per stage
  double newton_tolerance = 1e-7;
};

// Maximises log det C subject to a_i . d + |C a_i| <= b_i for every face of `poly` by damped
// Newton steps on the barrier function -log det C - mu sum log(b_i - a_i . d - |C a_i|) over
// the 9 unknowns (d, the 6 entries of the symmetric C); the problem is convex in (C, d) and
// tiny, so this needs no general solver. `start` must have its centre strictly inside `poly`
// (it is shrunk about its centre until it fits). Returns false if it cannot start.
bool inscribedEllipsoid(const Polytope& poly, const Ellipsoid& start, Ellipsoid* out,
                        const InscribedEllipsoidOptions& options = {});

}  // namespace mmh::som
