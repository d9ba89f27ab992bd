// The EAM objective over the control points of a uniform cubic B-spline (paper eq. 5, terms as
// in EGO-Planner): J = lambda1 Js + lambda2 Jc + lambda3 Jf with analytic gradients.
//   Js: jerk energy of the curve (the jerk is constant on each knot interval, so this is exact).
//   Jc: for every {p, v} anchor pair of a control point Q, a penalty on d = (Q - p) . v, the
//       signed distance past the obstacle surface along the repulsive direction, that is zero
//       for d >= the pair's clearance, cubic just below it and quadratic (C2-continued) deeper;
//       plus a cubic penalty on control points outside the geofence's walls (costSettingsFor).
//   Jf: squared excess of |V_i|^2 over v_max^2 and |A_i|^2 over a_max^2 for the velocity and
//       acceleration control points (the curve's velocity and acceleration lie in their convex
//       hulls, so satisfied terms bound the curve).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mmh/eam/eam_params.hpp"

namespace mmh::eam {

// Anchor point p on the obstacle surface, unit repulsive direction v (towards free space), and
// the clearance asked beyond p along v (at most half the free width there, so that the pairs of
// the two walls of a tight passage agree on its middle).
struct AnchorPair {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Vector3d v = Eigen::Vector3d::UnitX();
  double clearance = 0.1;
};
// Pairs per control point (index = control point index).
using PairSet = std::vector<std::vector<AnchorPair>>;

struct CostSettings {
  double max_vel_mps = 3.0;
  double max_acc_mps2 = 2.0;
  Eigen::Vector3d box_min = Eigen::Vector3d::Constant(-1e9);
  Eigen::Vector3d box_max = Eigen::Vector3d::Constant(1e9);
};

// The settings of a plan: the vehicle's limits, and the geofence with its walls
// geofence_margin_m inside it.
CostSettings costSettingsFor(const EamParams& p);

struct CostTerms {
  double smooth = 0.0;       // Js (m^2/s^5)
  double collision = 0.0;    // Jc
  double feasibility = 0.0;  // Jf
  double total = 0.0;        // weighted sum
};

// Penalty of one anchor pair as a function of c = clearance - d (zero for c <= 0), and its
// derivative with respect to c.
double collisionPenalty(double c, double clearance, double* derivative);

class BsplineCost {
 public:
  BsplineCost(const CostSettings& settings, const CostWeights& weights, const PairSet* pairs)
      : settings_(settings), weights_(weights), pairs_(pairs) {}

  // Cost of the control points q (3 x n) with knot span dt. If grad is given it receives
  // dJ/dq for every control point (the caller keeps the fixed ones fixed).
  CostTerms evaluate(const Eigen::Matrix3Xd& q, double dt, Eigen::Matrix3Xd* grad) const {
    return evaluate(q, dt, grad, 0, static_cast<int>(q.cols()) - 1);
  }
  // Only the terms that depend on a control point in [first, last]: the cost up to a constant
  // and the exact gradient for those points, when only they move (other columns of grad are
  // not meaningful).
  CostTerms evaluate(const Eigen::Matrix3Xd& q, double dt, Eigen::Matrix3Xd* grad, int first,
                     int last) const;

  const CostWeights& weights() const { return weights_; }
  void setWeights(const CostWeights& w) { weights_ = w; }

 private:
  double smoothness(const Eigen::Matrix3Xd& q, double dt, Eigen::Matrix3Xd* grad, double weight,
                    int first, int last) const;
  double collision(const Eigen::Matrix3Xd& q, Eigen::Matrix3Xd* grad, double weight, int first,
                   int last) const;
  double feasibility(const Eigen::Matrix3Xd& q, double dt, Eigen::Matrix3Xd* grad, double weight,
                     int first, int last) const;

  CostSettings settings_;
  CostWeights weights_;
  const PairSet* pairs_;
};

}  // namespace mmh::eam
