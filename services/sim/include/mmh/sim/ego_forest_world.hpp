// The EGO-Planner / Fast-Planner random forest (ego_forest.hpp) as a simulator world: the
// pillars' columns merged into a height map on their 0.1 m grid (ray casting walks it cell by
// cell, clearance is the exact distance to the column boxes) plus the rings' exact tubes. The
// time bound is a grid A* + line-of-sight shortening, as for point-cloud worlds, since the
// ragged tops and the rings make the shortest path three-dimensional.
#pragma once

#include <string>
#include <vector>

#include "mmh/sim/ego_forest.hpp"
#include "mmh/sim/world.hpp"

namespace mmh::sim {

struct EgoForestBoundOptions {
  double grid_m = 0.1;  // A* grid of the time bound
  // The bound's path stays in this box (the geofence) and within `corridor_margin_m` in x and y
  // of the box spanned by start and goal.
  Eigen::Vector3d min_m = Eigen::Vector3d(-1e4, -1e4, -1e4);
  Eigen::Vector3d max_m = Eigen::Vector3d(1e4, 1e4, 1e4);
  double corridor_margin_m = 10.0;
};

class EgoForestWorld : public World {
 public:
  EgoForestWorld(EgoForest forest, const EgoForestBoundOptions& bound);
  static EgoForestWorld generate(const EgoForestSpec& spec,
                                 const EgoForestBoundOptions& bound = {}) {
    return EgoForestWorld(generateEgoForest(spec), bound);
  }

  const EgoForest& forest() const { return forest_; }
  // Height of the column in grid cell (ix, iy): the tallest pillar column there, 0 if none.
  double columnHeight(int ix, int iy) const;

  void raycast(const Eigen::Vector3d& origin, const std::vector<Eigen::Vector3d>& dirs,
               double max_range, std::vector<double>* ranges) const override;
  // Exact distance to the nearest column box or ring tube (negative inside).
  double clearance(const Eigen::Vector3d& p) const override;
  double shortestPathLength(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            double radius) const override;
  std::string describe() const override;

 private:
  double castColumns(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                     double max_range) const;
  double columnClearance(const Eigen::Vector3d& p) const;

  EgoForest forest_;
  EgoForestBoundOptions bound_;
  int ix0_ = 0, iy0_ = 0, nx_ = 0, ny_ = 0;  // height map window (cells)
  std::vector<double> heights_;              // nx_ x ny_, x fastest
  size_t num_columns_ = 0;
};

}  // namespace mmh::sim
