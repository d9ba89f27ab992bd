// Hand-made, fully known worlds for the SOM tests: pillars, a wall with a gap, an S-bend and a
// target enclosed by walls, rasterised into a 0.1 m grid inflated by 0.3 m.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <vector>

#include "mmh/common/trajectory.hpp"
#include "mmh/common/voxel_grid.hpp"

namespace som_test {

struct World {
  std::shared_ptr<mmh::VoxelGrid> grid;
  Eigen::Vector3d start = Eigen::Vector3d(0.0, 0.0, 1.2);
  Eigen::Vector3d target = Eigen::Vector3d(12.0, 0.0, 1.2);
};

// Window x in [-2, 14], y in [-4, 4], z in [0, 3] at 0.1 m; cells inside `occupied` are occupied,
// all others free.
inline World makeWorld(const std::function<bool(const Eigen::Vector3d&)>& occupied,
                       double inflation_m = 0.3) {
  World w;
  w.grid = std::make_shared<mmh::VoxelGrid>(0.1, Eigen::Vector3i(-20, -40, 0),
                                            Eigen::Vector3i(160, 80, 30));
  for (int64_t i = 0; i < w.grid->numCells(); ++i) {
    const Eigen::Vector3d c = w.grid->centerOfLocal(w.grid->localFromLinear(i));
    w.grid->setLinear(i, occupied(c) ? mmh::Occupancy::kOccupied : mmh::Occupancy::kFree);
  }
  w.grid->setInflationRadius(inflation_m);
  return w;
}

// A start state at rest at p.
inline mmh::KinematicState atRest(const Eigen::Vector3d& p) {
  mmh::KinematicState s;
  s.position = p;
  return s;
}

inline bool inCylinder(const Eigen::Vector3d& p, double x, double y, double r) {
  return std::hypot(p.x() - x, p.y() - y) <= r;
}

inline bool inBox(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
}

// 14 pillars of radius 0.15-0.5 m scattered between start and target (x in [2, 10], y in
// [-3, 3]), the same for the same seed.
inline World randomPillars(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(2.0, 10.0), uy(-3.0, 3.0), ur(0.15, 0.5);
  std::vector<Eigen::Vector3d> pillars;  // x, y, radius
  for (int k = 0; k < 14; ++k) pillars.emplace_back(ux(rng), uy(rng), ur(rng));
  return makeWorld([&](const Eigen::Vector3d& p) {
    for (const auto& c : pillars)
      if (inCylinder(p, c.x(), c.y(), c.z())) return true;
    return false;
  });
}

inline World pillars() {
  return makeWorld([](const Eigen::Vector3d& p) {
    return inCylinder(p, 3.0, 0.2, 0.3) || inCylinder(p, 5.0, -0.7, 0.4) ||
           inCylinder(p, 6.5, 1.0, 0.35) || inCylinder(p, 8.0, 0.0, 0.3) ||
           inCylinder(p, 10.0, -0.9, 0.3) || inCylinder(p, 9.8, 1.2, 0.25);
  });
}

// A wall across the whole window at x = 6 with a 1.2 m gap at y in [1.0, 2.2].
inline World wallWithGap() {
  return makeWorld([](const Eigen::Vector3d& p) {
    return p.x() >= 5.9 && p.x() <= 6.1 && !(p.y() >= 1.0 && p.y() <= 2.2);
  });
}

// Two walls whose gaps are at opposite sides: the way from start to target is an S.
inline World sBend() {
  return makeWorld([](const Eigen::Vector3d& p) {
    const bool wall_a = p.x() >= 3.9 && p.x() <= 4.1 && p.y() <= 1.8;
    const bool wall_b = p.x() >= 7.9 && p.x() <= 8.1 && p.y() >= -1.8;
    return wall_a || wall_b;
  });
}

// The target sits in a closed room (walls, floor and ceiling beyond the geofence band).
inline World targetEnclosed() {
  return makeWorld([](const Eigen::Vector3d& p) {
    const Eigen::Vector3d c(12.0, 0.0, 1.2);
    const bool outer =
        inBox(p, c - Eigen::Vector3d(1.2, 1.2, 1.5), c + Eigen::Vector3d(1.2, 1.2, 1.8));
    const bool inner =
        inBox(p, c - Eigen::Vector3d(1.0, 1.0, 1.3), c + Eigen::Vector3d(1.0, 1.0, 1.6));
    return outer && !inner;
  });
}

}  // namespace som_test
