// Spatio-temporal MINCO optimisation inside a safe flight corridor (after Wang et al., T-RO
// 2022): minimum-jerk pieces, one or more per polytope, whose intermediate waypoints and
// durations are optimised together by L-BFGS (NLopt LD_LBFGS) on
//   J = int |jerk|^2 dt + rho T + penalties,
// durations through the smooth map of time_map.hpp, and corridor membership, |v| <= v_max and
// |a| <= a_max as C2 smoothed exact (L1) penalties with high weights on densely sampled points
// (waypoints are samples of both pieces they join, hence kept in the polytope overlaps).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mmh/common/minco.hpp"
#include "mmh/common/trajectory.hpp"
#include "mmh/som/corridor.hpp"
#include "mmh/som/params.hpp"

namespace mmh::som {

struct OptimizerOutput {
  Trajectory trajectory;
  std::vector<int> piece_polytope;  // polytope index of each piece
  double cost_total = 0.0;
  double cost_control = 0.0;  // int |jerk|^2 dt
  double cost_time = 0.0;     // rho T
  double cost_penalty = 0.0;  // residual constraint penalties
  int evaluations = 0;
  int nlopt_result = 0;  // nlopt_result code of the last run
  int repairs = 0;       // time-stretch steps needed to meet the limits exactly
  int extra_rounds = 0;  // runs with a raised corridor or limit weight
  std::string message;
};

// Initial segment durations along a polyline: a speed profile from v0 (along the first segment)
// to rest at the end within a and vm that slows down at every corner to sqrt(a r), r the radius
// of the arc tangent to both segments at half the shorter one.
std::vector<double> cornerAwareDurations(const std::vector<Eigen::Vector3d>& points, double v0,
                                         double vm, double a);

// C2 smoothed L1 penalty: 0 for x <= 0, cubic on (0, mu), x - mu/2 beyond; *grad = f'(x).
double smoothedL1(double x, double mu, double* grad);

class TrajectoryOptimizer {
 public:
  TrajectoryOptimizer(const OptimizerParams& params, double max_vel_mps, double max_acc_mps2);
  void setMaxVel(double max_vel_mps) { max_vel_ = max_vel_mps; }

  // Pieces and initial guess for a trajectory from `start` to `target` (at rest) through the
  // corridor. False if the corridor is empty.
  bool setup(const KinematicState& start, const Eigen::Vector3d& target, const Corridor& corridor);
  // Runs L-BFGS from the initial guess. False (with a message) if it produced no finite result.
  bool optimize(OptimizerOutput* out);

  // The objective at x = (inner waypoints, column by column; tau of each piece) and its
  // gradient (if grad is not null). Exposed for tests.
  double objective(const Eigen::VectorXd& x, Eigen::VectorXd* grad);
  const Eigen::VectorXd& initialGuess() const { return x0_; }
  int numPieces() const { return pieces_; }
  // The MINCO trajectory at x (no repair) and the polytope of each piece (for tests).
  Trajectory trajectoryAt(const Eigen::VectorXd& x);
  const std::vector<int>& piecePolytope() const { return piece_polytope_; }
  // The objective's parts at x: control effort, rho T, penalties.
  void costParts(const Eigen::VectorXd& x, double* control, double* time, double* penalty);

 private:
  static double nloptObjective(unsigned n, const double* x, double* grad, void* data);
  // One L-BFGS run from x (replaced by the best point found); returns its cost.
  double runNlopt(Eigen::VectorXd& x, int max_evaluations, int* result, std::string* message);
  // Worst distance outside its polytope over samples twice as dense as the penalty's.
  double corridorViolation(const Eigen::VectorXd& x);
  // The time stretch the maxima at x call for: max(v / v_max, sqrt(a / a_max)).
  double limitExcess(const Eigen::VectorXd& x);
  // Max speed and acceleration over 32 samples per piece.
  static void sampledMaxima(const Trajectory& traj, double* speed, double* acc);
  double evaluate(const Eigen::VectorXd& x, Eigen::VectorXd* grad, double* control, double* time,
                  double* penalty);

  OptimizerParams params_;
  double max_vel_, max_acc_;
  double corridor_boost_ = 1.0;  // multiply the corridor / limit weights in extra rounds
  double limit_boost_ = 1.0;
  // A start at rest: stretching all durations scales speeds and accelerations exactly, so the
  // final stretch can fix any excess; a moving start fixes its first moments.
  bool moving_start_ = false;
  const Corridor* corridor_ = nullptr;
  int pieces_ = 0;
  std::vector<int> piece_polytope_;
  Eigen::Matrix3d head_, tail_;
  Eigen::VectorXd x0_;
  MincoJerk minco_;
  // Workspace.
  Eigen::Matrix3Xd points_, grad_points_;
  Eigen::VectorXd durations_, grad_durations_, grad_total_;
  Eigen::MatrixX3d grad_coeffs_;
  // Per polytope, an ellipsoid {d + C u : |u| <= r} inside which every face is met with the
  // corridor margin to spare, so that the penalty need not test the faces there: C^-1, d and r^2
  // (r^2 < 0: none).
  struct InnerRegion {
    Eigen::Matrix3d to_unit;
    Eigen::Vector3d center;
    double radius2 = -1.0;
  };
  std::vector<InnerRegion> inner_;
  static InnerRegion innerRegion(const Polytope& poly, const Ellipsoid& ellipsoid, double margin_m);
  Eigen::VectorXd xbuf_, gbuf_;
  int evaluations_ = 0;
};

}  // namespace mmh::som
