// Where a fast start's second candidate path begins: a point ahead along the velocity, within
// reach of the way the vehicle is already going. SOM's A* path ignores the velocity; when it
// turns sharply away, the corridor lets the optimiser brake nearly to rest and come back (a
// U-turn of seconds), while a path that first goes on ahead often swerves instead.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "mmh/common/trajectory.hpp"
#include "mmh/common/voxel_grid.hpp"

namespace mmh::som {

struct LeadPointParams {
  double min_speed_mps = 1.0;  // slower starts turn on the spot well enough
  double min_turn_deg = 45.0;  // only when the A* path's first leg turns away by more than this
  double reach = 1.5;          // the point lies this many braking distances ahead, at most
};

// Whether the A* path from `start` turns away from its velocity enough for a second candidate.
bool turnsAwayFromVelocity(const KinematicState& start, const Eigen::Vector3d& first_path_point,
                           const LeadPointParams& params);

// The farthest point along the velocity, at most reach x the braking distance at max_acc_mps2
// and at least 0.3 m ahead, on a straight line free of blocked cells, inside [lo, hi] and the
// grid's window (sampled a voxel apart, nearest first from the far end); none if there is none.
std::optional<Eigen::Vector3d> leadPoint(const VoxelGrid& grid, const KinematicState& start,
                                         double max_acc_mps2, const Eigen::Vector3d& lo,
                                         const Eigen::Vector3d& hi, const LeadPointParams& params);

}  // namespace mmh::som
