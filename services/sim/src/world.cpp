#include "mmh/sim/world.hpp"

namespace mmh::sim {

double World::raycastOne(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                         double max_range) const {
  std::vector<double> ranges;
  raycast(origin, {dir}, max_range, &ranges);
  return ranges.front();
}

}  // namespace mmh::sim
