// Piecewise-polynomial 3-D trajectory: the one trajectory type every mode produces and the
// arbiter, the simulator and the checks consume. Pieces have degree <= 7.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace mmh {

constexpr int kMaxPolyOrder = 8;                              // coefficients per axis (degree 7)
using PieceCoeffs = Eigen::Matrix<double, 3, kMaxPolyOrder>;  // row = axis, col k = t^k

struct KinematicState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();
};

struct Piece {
  double duration = 0.0;
  PieceCoeffs coeffs = PieceCoeffs::Zero();

  // Derivative `order` (0 = position) at local time t in [0, duration].
  Eigen::Vector3d derivative(int order, double t) const;
  Eigen::Vector3d position(double t) const { return derivative(0, t); }
  Eigen::Vector3d velocity(double t) const { return derivative(1, t); }
  Eigen::Vector3d acceleration(double t) const { return derivative(2, t); }
  Eigen::Vector3d jerk(double t) const { return derivative(3, t); }
  // Same curve re-parameterised to start at local time t0 (Taylor shift of the coefficients).
  Piece shifted(double t0) const;
};

class Trajectory {
 public:
  Trajectory() = default;
  explicit Trajectory(std::vector<Piece> pieces) : pieces_(std::move(pieces)) {}

  bool empty() const { return pieces_.empty(); }
  int numPieces() const { return static_cast<int>(pieces_.size()); }
  const std::vector<Piece>& pieces() const { return pieces_; }
  std::vector<Piece>& pieces() { return pieces_; }
  void append(const Piece& p) { pieces_.push_back(p); }

  double duration() const;
  // Times are relative to the trajectory start and clamped to [0, duration()].
  Eigen::Vector3d derivative(int order, double t) const;
  Eigen::Vector3d position(double t) const { return derivative(0, t); }
  Eigen::Vector3d velocity(double t) const { return derivative(1, t); }
  Eigen::Vector3d acceleration(double t) const { return derivative(2, t); }
  Eigen::Vector3d jerk(double t) const { return derivative(3, t); }
  KinematicState state(double t) const;

  // Arc length between t0 and t1 (Gauss-Legendre per piece, subdivided; error < 1e-9 m for
  // trajectories of this project).
  double arcLength(double t0, double t1) const;
  double arcLength() const { return arcLength(0.0, duration()); }
  // Integral of |jerk|^2 over the whole trajectory, exact (polynomial integral).
  double jerkEnergy() const;
  // Exact maxima of |velocity| and |acceleration| (stationary points of the squared norm).
  double maxSpeed(double* at_time = nullptr) const;
  double maxAcceleration(double* at_time = nullptr) const;
  double maxJerk(double* at_time = nullptr) const;
  // Part from t0 to the end, re-based so that it starts at time 0.
  Trajectory tail(double t0) const;
  // Part from the start to t1.
  Trajectory head(double t1) const;
  // All coefficients and durations finite, durations positive.
  bool isFinite() const;

 private:
  // Piece index and local time for a trajectory time.
  int locate(double t, double* local) const;
  std::vector<Piece> pieces_;
};

}  // namespace mmh
