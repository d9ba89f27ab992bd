// The FPM optimisation (paper eq. 1-2, after Wang et al., RA-L 2020): the free knot states D_P
// (position, velocity, acceleration at the inner knots) and the piece durations T of a piecewise
// quintic minimise  int |jerk|^2 dt + rho T  plus smooth penalties on speed and acceleration
// above their limits, sampled along every piece. Solved with NLopt's L-BFGS on analytic
// gradients; durations go through the time map so that they stay positive. Each piece depends
// only on its two knots, so a cost evaluation is O(pieces) with no linear system.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mmh/fpm/hermite_pieces.hpp"

namespace mmh::fpm {

struct OptimizerSettings {
  double v_limit = 3.0, a_limit = 2.0;  // where the penalties start
  double time_weight = 1000.0;          // rho
  double penalty_weight = 1e4;
  int samples_per_piece = 10;  // at most; about one sample interval per 0.1 s, at least 2
  int max_evaluations = 100;
  double relative_tolerance = 1e-6;  // stop when the cost improves less than this (relative)
};

struct CostBreakdown {
  double control = 0.0;  // int |jerk|^2 dt
  double time = 0.0;     // rho T
  double penalty = 0.0;  // limit-violation penalties
  double total() const { return control + time + penalty; }
};

class SpatioTemporalOptimizer {
 public:
  // knots: first = start state, last = end state (both kept); fixed_position[i] keeps the
  // position of inner knot i (a waypoint). durations: knots.size() - 1 values > 0.
  void setup(const std::vector<KnotState>& knots, const std::vector<bool>& fixed_position,
             const Eigen::VectorXd& durations);
  // Restrict the inner knots to the affine subspace through `origin` spanned by the orthonormal
  // columns of `basis` (1 column: a line, 2: a plane). When the start state and the target lie
  // in it (and there are no waypoints), the problem is symmetric under the reflections that fix
  // it, so the optimum stays in it: one or two variables per knot quantity instead of three.
  // Call after setup().
  void restrictTo(const Eigen::Vector3d& origin, const Eigen::Matrix3Xd& basis);

  // L-BFGS from the current variables; keeps the best point found. Returns the number of cost
  // evaluations.
  int optimize(const OptimizerSettings& settings);

  const std::vector<KnotState>& knots() const { return knots_; }
  const Eigen::VectorXd& durations() const { return durations_; }
  Trajectory trajectory() const { return hermiteTrajectory(knots_, durations_); }
  CostBreakdown costs(const OptimizerSettings& settings);

  // Cost (unscaled) and its gradient w.r.t. the packed variables (tests check it against finite
  // differences). x: for each inner knot [p unless fixed, v, a] (3 values each, or 1 on a line),
  // then one tau per piece.
  double evaluate(const std::vector<double>& x, std::vector<double>* grad);
  std::vector<double> pack() const;
  void setSettings(const OptimizerSettings& settings);

 private:
  double evaluateRaw(const double* x, double* grad, CostBreakdown* breakdown);
  static double nloptObjective(unsigned n, const double* x, double* grad, void* data);
  void unpack(const double* x);
  void countVariables();

  std::vector<KnotState> knots_;
  std::vector<bool> fixed_;
  // Subspace the inner knots live in (identity basis: all of space).
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3Xd basis_ = Eigen::Matrix3d::Identity();
  Eigen::VectorXd durations_;
  OptimizerSettings settings_;
  std::vector<int> samples_;  // sample intervals per piece
  int num_vars_ = 0;
  int evaluations_ = 0;
  double scale_ = 1.0;  // cost scale seen by NLopt (largest initial partial derivative -> 1)
  double best_cost_ = 0.0;
  std::vector<double> best_x_;
  // Workspace: gradients per knot and per piece.
  std::vector<KnotState> grad_knots_;
  Eigen::VectorXd grad_durations_;
};

}  // namespace mmh::fpm
