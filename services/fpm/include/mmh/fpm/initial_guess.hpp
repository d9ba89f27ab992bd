// Initial guess of the FPM optimisation: knot states and durations sampled from jerk-limited
// ("S-curve") speed profiles along the straight path start -> waypoints -> target, plus a lateral
// profile that brings a sideways start velocity to rest. Knots sit where the profiles' jerk
// changes, so the quintic pieces reproduce the profiles exactly: for a start moving along the
// path the guess is already feasible and close to time-optimal, and the optimiser only polishes.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mmh/common/trajectory.hpp"
#include "mmh/fpm/hermite_pieces.hpp"

namespace mmh::fpm {

struct InitialGuess {
  std::vector<KnotState> knots;   // start, inner knots, end (target at rest)
  std::vector<bool> fixed;        // per inner knot: a waypoint (its position stays)
  Eigen::VectorXd durations;      // knots.size() - 1
  double profile_duration = 0.0;  // the trapezoid along the path: a lower bound on the duration
};

struct GuessOptions {
  double v_max = 3.0, a_max = 2.0;  // limits of the profiles (already with margins)
  double ramp_s = 0.15;             // acceleration ramps of the S-curves
  double max_piece_s = 3.0;         // longer stretches are split
  double min_piece_s = 0.02;        // knots closer than this are merged
};

InitialGuess makeInitialGuess(const KinematicState& start, const Eigen::Vector3d& target,
                              const std::vector<Eigen::Vector3d>& waypoints,
                              const GuessOptions& options);

}  // namespace mmh::fpm
