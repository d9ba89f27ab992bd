// Ground truth of a simulated world: what the sensors ray-cast against, what the vehicle collides
// with, and the shortest collision-free path that bounds the mission time. Implemented by the
// random forest (ForestWorld) and by point clouds from PCD files (PointCloudWorld).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace mmh::sim {

class World {
 public:
  virtual ~World() = default;

  // For each unit direction in `dirs` (world frame), the distance from `origin` to the first
  // obstacle surface, or a negative value if there is none within `max_range`.
  virtual void raycast(const Eigen::Vector3d& origin, const std::vector<Eigen::Vector3d>& dirs,
                       double max_range, std::vector<double>* ranges) const = 0;
  double raycastOne(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                    double max_range) const;

  // Distance from p to the nearest obstacle surface (<= 0 inside an obstacle); +inf if the world
  // is empty.
  virtual double clearance(const Eigen::Vector3d& p) const = 0;

  // Length of the shortest path from a to b that keeps a sphere of `radius` free of obstacles
  // (exact for forests, grid A* + shortening for point clouds); negative if there is none.
  virtual double shortestPathLength(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    double radius) const = 0;

  virtual std::string describe() const = 0;
};

}  // namespace mmh::sim
