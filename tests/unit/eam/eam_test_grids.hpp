// Hand-made maps for the EAM tests and an independent collision check of a trajectory.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "mmh/common/trajectory.hpp"
#include "mmh/common/voxel_grid.hpp"

namespace eam_test {

// 16 x 8 x 3 m window (x in [-2, 14], y in [-4, 4], z in [0, 3]) at 0.1 m, all free, inflated
// by 0.3 m like the default configuration.
inline mmh::VoxelGrid freeGrid() {
  mmh::VoxelGrid g(0.1, Eigen::Vector3i(-20, -40, 0), Eigen::Vector3i(160, 80, 30));
  g.setInflationRadius(0.3);
  for (int64_t i = 0; i < g.numCells(); ++i) g.setLinear(i, mmh::Occupancy::kFree);
  return g;
}

// Vertical cylinder through the whole window.
inline void addPillar(mmh::VoxelGrid& g, double x, double y, double radius) {
  for (int64_t i = 0; i < g.numCells(); ++i) {
    const Eigen::Vector3d c = g.centerOfLocal(g.localFromLinear(i));
    if (std::hypot(c.x() - x, c.y() - y) <= radius) g.setLinear(i, mmh::Occupancy::kOccupied);
  }
}

// Wall across the window at x in [x0, x0 + thickness], with an opening for |y - gap_y| < gap / 2.
inline void addWallWithGap(mmh::VoxelGrid& g, double x0, double thickness, double gap_y,
                           double gap) {
  for (int64_t i = 0; i < g.numCells(); ++i) {
    const Eigen::Vector3d c = g.centerOfLocal(g.localFromLinear(i));
    if (c.x() >= x0 && c.x() <= x0 + thickness && std::abs(c.y() - gap_y) >= 0.5 * gap)
      g.setLinear(i, mmh::Occupancy::kOccupied);
  }
}

// First time at which the trajectory is inside the inflated (or, with occupied_only, the raw)
// obstacles, sampling at most 1 cm apart; -1 if never. Written here so that the tests do not
// rely on the planner's own checks.
inline double firstBlockedTime(const mmh::VoxelGrid& g, const mmh::Trajectory& traj,
                               bool occupied_only) {
  const double vmax = std::max(1e-3, traj.maxSpeed());
  const double dt = 0.01 / vmax;
  for (double t = 0.0; t <= traj.duration() + 1e-12; t += dt) {
    const Eigen::Vector3d p = traj.position(std::min(t, traj.duration()));
    if (occupied_only ? g.isOccupiedPoint(p) : g.isBlockedPoint(p)) return t;
  }
  return -1.0;
}

// Smallest horizontal distance of the trajectory to a pillar's axis (sampled every 1 cm).
inline double minDistanceToAxis(const mmh::Trajectory& traj, double x, double y) {
  const double vmax = std::max(1e-3, traj.maxSpeed());
  double best = 1e9;
  for (double t = 0.0; t <= traj.duration(); t += 0.01 / vmax) {
    const Eigen::Vector3d p = traj.position(t);
    best = std::min(best, std::hypot(p.x() - x, p.y() - y));
  }
  return best;
}

// Straight rest-to-rest quintic from a to b over T seconds.
inline mmh::Trajectory straightLine(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double T) {
  mmh::Piece p;
  p.duration = T;
  const Eigen::Vector3d d = b - a;
  p.coeffs.col(0) = a;
  p.coeffs.col(3) = 10.0 * d / std::pow(T, 3);
  p.coeffs.col(4) = -15.0 * d / std::pow(T, 4);
  p.coeffs.col(5) = 6.0 * d / std::pow(T, 5);
  return mmh::Trajectory({p});
}

}  // namespace eam_test
