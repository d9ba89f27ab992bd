#include "mmh/common/trajectory.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "mmh/common/polynomial.hpp"
#include "mmh/common/trajectory_limits.hpp"

namespace mmh {

Eigen::Vector3d Piece::derivative(int order, double t) const {
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  for (int k = kMaxPolyOrder - 1; k >= order; --k) {
    r = r * t + coeffs.col(k) * fallingFactorial(k, order);
  }
  return r;
}

Piece Piece::shifted(double t0) const {
  // p(t + t0) = sum_k c_k (t + t0)^k = sum_j t^j sum_{k>=j} c_k C(k, j) t0^(k-j).
  Piece out;
  out.duration = duration - t0;
  for (int j = 0; j < kMaxPolyOrder; ++j) {
    Eigen::Vector3d acc = Eigen::Vector3d::Zero();
    double binom = 1.0;  // C(k, j) for k = j
    double power = 1.0;  // t0^(k - j)
    for (int k = j; k < kMaxPolyOrder; ++k) {
      acc += coeffs.col(k) * binom * power;
      binom = binom * (k + 1) / (k + 1 - j);
      power *= t0;
    }
    out.coeffs.col(j) = acc;
  }
  return out;
}

double Trajectory::duration() const {
  double d = 0.0;
  for (const Piece& p : pieces_) d += p.duration;
  return d;
}

int Trajectory::locate(double t, double* local) const {
  if (pieces_.empty()) {
    *local = 0.0;
    return -1;
  }
  if (t <= 0.0) {
    *local = 0.0;
    return 0;
  }
  for (int i = 0; i < numPieces(); ++i) {
    if (t <= pieces_[i].duration || i + 1 == numPieces()) {
      *local = std::min(t, pieces_[i].duration);
      return i;
    }
    t -= pieces_[i].duration;
  }
  *local = pieces_.back().duration;
  return numPieces() - 1;
}

Eigen::Vector3d Trajectory::derivative(int order, double t) const {
  double local = 0.0;
  int i = locate(t, &local);
  if (i < 0) return Eigen::Vector3d::Zero();
  return pieces_[i].derivative(order, local);
}

KinematicState Trajectory::state(double t) const {
  return KinematicState{position(t), velocity(t), acceleration(t)};
}

double Trajectory::arcLength(double t0, double t1) const {
  // 5-point Gauss-Legendre on sub-intervals of at most 0.05 s: speed is a smooth function of
  // time within a piece, so this is accurate far below a millimetre.
  static const std::array<double, 5> nodes = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                              0.5384693101056831, 0.9061798459386640};
  static const std::array<double, 5> weights = {0.2369268850561891, 0.4786286704993665,
                                                0.5688888888888889, 0.4786286704993665,
                                                0.2369268850561891};
  t0 = std::max(0.0, t0);
  t1 = std::min(duration(), t1);
  double length = 0.0, start = 0.0;
  for (const Piece& piece : pieces_) {
    double a = std::max(t0, start), b = std::min(t1, start + piece.duration);
    if (b > a) {
      int n = std::max(1, static_cast<int>(std::ceil((b - a) / 0.05)));
      double h = (b - a) / n;
      for (int s = 0; s < n; ++s) {
        double mid = a - start + (s + 0.5) * h;
        for (int q = 0; q < 5; ++q) {
          length += 0.5 * h * weights[q] * piece.velocity(mid + 0.5 * h * nodes[q]).norm();
        }
      }
    }
    start += piece.duration;
  }
  return length;
}

double Trajectory::jerkEnergy() const {
  double e = 0.0;
  for (const Piece& piece : pieces_)
    e += polyIntegral(squaredDerivativeNormPoly(piece, 3), piece.duration);
  return e;
}

double Trajectory::maxSpeed(double* at_time) const {
  return maxDerivativeNorm(*this, 1, at_time);
}
double Trajectory::maxAcceleration(double* at_time) const {
  return maxDerivativeNorm(*this, 2, at_time);
}
double Trajectory::maxJerk(double* at_time) const {
  return maxDerivativeNorm(*this, 3, at_time);
}

Trajectory Trajectory::tail(double t0) const {
  Trajectory out;
  double local = 0.0;
  int i = locate(t0, &local);
  if (i < 0) return out;
  Piece first = pieces_[i].shifted(local);
  if (first.duration > 1e-9 || i + 1 == numPieces()) out.append(first);
  for (int j = i + 1; j < numPieces(); ++j) out.append(pieces_[j]);
  return out;
}

Trajectory Trajectory::head(double t1) const {
  Trajectory out;
  double local = 0.0;
  const int i = locate(t1, &local);
  for (int j = 0; j < i; ++j) out.append(pieces_[j]);
  if (i >= 0 && (local > 1e-9 || out.empty())) {
    Piece last = pieces_[i];
    last.duration = local;
    out.append(last);
  }
  return out;
}

bool Trajectory::isFinite() const {
  for (const Piece& p : pieces_) {
    if (!std::isfinite(p.duration) || p.duration <= 0.0 || !p.coeffs.allFinite()) return false;
  }
  return true;
}

}  // namespace mmh
