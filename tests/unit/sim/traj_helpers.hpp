// Small trajectories with known answers for the simulator, setpoint and arbiter tests.
#pragma once

#include <memory>

#include "mmh/common/minco.hpp"
#include "mmh/common/trajectory.hpp"

namespace mmh::test {

// p(t) = p0 + v t for t in [0, duration].
inline std::shared_ptr<const Trajectory> line(const Eigen::Vector3d& p0, const Eigen::Vector3d& v,
                                              double duration) {
  Piece piece;
  piece.duration = duration;
  piece.coeffs.col(0) = p0;
  piece.coeffs.col(1) = v;
  return std::make_shared<const Trajectory>(std::vector<Piece>{piece});
}

// Rest-to-rest quintic (minimum jerk) from a to b in time T.
inline Piece minJerk(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double T) {
  Piece piece;
  piece.duration = T;
  const Eigen::Vector3d d = b - a;
  piece.coeffs.col(0) = a;
  piece.coeffs.col(3) = 10.0 * d / std::pow(T, 3);
  piece.coeffs.col(4) = -15.0 * d / std::pow(T, 4);
  piece.coeffs.col(5) = 6.0 * d / std::pow(T, 5);
  return piece;
}

inline std::shared_ptr<const Trajectory> minJerkTraj(const Eigen::Vector3d& a,
                                                     const Eigen::Vector3d& b, double T) {
  return std::make_shared<const Trajectory>(std::vector<Piece>{minJerk(a, b, T)});
}

// Rest-ending quintic from any state `start` to rest at `target` in T seconds (one MINCO piece):
// what a mode answers, starting in the requested state.
inline Trajectory planFrom(const KinematicState& start, const Eigen::Vector3d& target, double T) {
  MincoJerk m;
  Eigen::Matrix3d head, tail;
  head << start.position, start.velocity, start.acceleration;
  tail << target, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero();
  m.setConditions(head, tail, 1);
  m.setParameters(Eigen::Matrix3Xd(3, 0), Eigen::VectorXd::Constant(1, T));
  return m.trajectory();
}

}  // namespace mmh::test
