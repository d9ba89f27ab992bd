// EAM's initial guess: the rest of the committed trajectory, or a straight rest-to-rest quintic
// when there is none, sampled into the control points of a uniform cubic B-spline whose first
// three control points reproduce the start state and whose last three hold the target at rest.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mmh/common/trajectory.hpp"
#include "mmh/eam/uniform_bspline.hpp"

namespace mmh::eam {

// Quintic from the start state to the target at rest, on the shortest duration (10% steps) whose
// exact maxima stay within the limits (or within the start state's own values if those are higher).
Trajectory straightQuintic(const KinematicState& start, const Eigen::Vector3d& target,
                           double max_vel_mps, double max_acc_mps2);

// Uniform cubic B-spline following `guess` (whose duration sets the timing): K = ceil(T / span)
// intervals (clamped to [min_segments, max_segments]) of dt = T / K; Q_0..Q_2 from the start
// state, Q_K..Q_{K+2} = target, and in between Q_i = c(t) - dt^2/6 c''(t) at t = (i - 1) dt,
// which makes the spline pass within O(dt^4) of c at the knots.
UniformBspline sampleToBspline(const Trajectory& guess, const KinematicState& start,
                               const Eigen::Vector3d& target, double knot_span_s,
                               int min_segments = 6, int max_segments = 300);

// Uniform cubic B-spline along a polyline (an A* path from the start to the target): a speed
// profile from the start's speed up to v_max and down to rest at a_max over the path's length
// sets the duration, so K = ceil(T / span) intervals; Q_0..Q_2 from the start state,
// Q_K..Q_{K+2} = target, in between Q_i = the path point reached at t = (i - 1) dt. The
// straight guess's duration gives a detour far longer than the straight line too few control
// points to bend around the obstacles.
UniformBspline sampleAlongPath(const std::vector<Eigen::Vector3d>& path,
                               const KinematicState& start, const Eigen::Vector3d& target,
                               double knot_span_s, double max_vel_mps, double max_acc_mps2,
                               int min_segments = 6, int max_segments = 300);

}  // namespace mmh::eam
