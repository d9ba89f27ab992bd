// The random forest world of the benchmark protocol: vertical cylinders (common/forest.hpp),
// ray-cast analytically (side and caps) and with the exact 2-D shortest path around them.
#pragma once

#include <vector>

#include "mmh/common/forest.hpp"
#include "mmh/sim/world.hpp"

namespace mmh::sim {

class ForestWorld : public World {
 public:
  explicit ForestWorld(std::vector<Cylinder> cylinders);
  static ForestWorld generate(const ForestSpec& spec) { return ForestWorld(generateForest(spec)); }

  const std::vector<Cylinder>& cylinders() const { return cylinders_; }

  void raycast(const Eigen::Vector3d& origin, const std::vector<Eigen::Vector3d>& dirs,
               double max_range, std::vector<double>* ranges) const override;
  // Exact 3-D distance to the nearest cylinder (side, caps, rims).
  double clearance(const Eigen::Vector3d& p) const override;
  // Exact: cylinders are full height, so the path is the 2-D shortest path among discs inflated
  // by `radius` (shortestPathAmongDiscs), with the height difference added in quadrature. Worlds
  // with more than 4000 cylinders (far denser than the protocol) use a 0.1 m planar grid A*.
  double shortestPathLength(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            double radius) const override;
  std::string describe() const override;

 private:
  std::vector<Cylinder> cylinders_;
};

// Distance along the unit ray origin + t dir to the surface of a finite vertical cylinder, or a
// negative value if it misses; 0 if the origin is inside.
double rayCylinder(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, const Cylinder& c);

}  // namespace mmh::sim
