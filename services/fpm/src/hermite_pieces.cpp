#include "mmh/fpm/hermite_pieces.hpp"

namespace mmh::fpm {

QuinticCoeffs hermiteQuintic(const KnotState& a, const KnotState& b, double T) {
  const double T2 = T * T, T3 = T2 * T, T4 = T3 * T, T5 = T4 * T;
  const Eigen::Vector3d dp = b.p - a.p;
  QuinticCoeffs c;
  c.col(0) = a.p;
  c.col(1) = a.v;
  c.col(2) = 0.5 * a.a;
  c.col(3) = 10.0 * dp / T3 - (4.0 * b.v + 6.0 * a.v) / T2 - (1.5 * a.a - 0.5 * b.a) / T;
  c.col(4) = -15.0 * dp / T4 + (7.0 * b.v + 8.0 * a.v) / T3 + (1.5 * a.a - b.a) / T2;
  c.col(5) = 6.0 * dp / T5 - 3.0 * (b.v + a.v) / T4 - 0.5 * (a.a - b.a) / T3;
  return c;
}

Trajectory hermiteTrajectory(const std::vector<KnotState>& knots,
                             const Eigen::VectorXd& durations) {
  Trajectory traj;
  for (int i = 0; i < durations.size(); ++i) {
    Piece piece;
    piece.duration = durations[i];
    piece.coeffs.leftCols(6) = hermiteQuintic(knots[i], knots[i + 1], durations[i]);
    traj.append(piece);
  }
  return traj;
}

double quinticJerkEnergy(const QuinticCoeffs& c, double T) {
  const Eigen::Vector3d c3 = c.col(3), c4 = c.col(4), c5 = c.col(5);
  const double T2 = T * T, T3 = T2 * T, T4 = T3 * T, T5 = T4 * T;
  return 36.0 * c3.squaredNorm() * T + 144.0 * c3.dot(c4) * T2 + 192.0 * c4.squaredNorm() * T3 +
         240.0 * c3.dot(c5) * T3 + 720.0 * c4.dot(c5) * T4 + 720.0 * c5.squaredNorm() * T5;
}

}  // namespace mmh::fpm
