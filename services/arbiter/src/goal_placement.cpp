#include "mmh/arbiter/goal_placement.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <tuple>
#include <vector>

#include "mmh/arbiter/local_target.hpp"

namespace mmh::arbiter {
namespace {

std::string point(const Eigen::Vector3d& p) {
  std::ostringstream out;
  out.precision(3);
  out << std::fixed << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return out.str();
}

}  // namespace

GoalPlacement placeGoal(const VoxelGrid& grid, const Eigen::Vector3d& goal, double clearance_m,
                        double radius_m, const Eigen::Vector3d& fence_min,
                        const Eigen::Vector3d& fence_max) {
  GoalPlacement out;
  out.position = goal;
  if (isClearOf(grid, goal, clearance_m)) {
    out.ok = true;
    return out;
  }
  // Candidates: the cell centres within the radius, nearest first.
  const double res = grid.resolution();
  const Eigen::Vector3i centre = grid.globalIndexOf(goal);
  const int r = static_cast<int>(std::ceil(radius_m / res)) + 1;
  // distance (in nm, so that equal distances tie exactly), z, y, x
  std::vector<std::tuple<int64_t, double, double, double>> candidates;
  for (int z = -r; z <= r; ++z)
    for (int y = -r; y <= r; ++y)
      for (int x = -r; x <= r; ++x) {
        const Eigen::Vector3d p =
            ((centre + Eigen::Vector3i(x, y, z)).cast<double>().array() + 0.5).matrix() * res;
        const double d = (p - goal).norm();
        if (d > radius_m) continue;
        if ((p.array() < fence_min.array()).any() || (p.array() > fence_max.array()).any())
          continue;
        candidates.emplace_back(std::llround(d * 1e9), p.z(), p.y(), p.x());
      }
  std::sort(candidates.begin(), candidates.end());
  std::ostringstream asked_text;
  asked_text.precision(2);
  asked_text << std::fixed << "goal " << point(goal) << " lies inside a mapped obstacle or within "
             << clearance_m << " m (map.inflation_m) of one";
  const std::string asked = asked_text.str();
  for (const auto& [distance_nm, z, y, x] : candidates) {
    const Eigen::Vector3d p(x, y, z);
    if (!isClearOf(grid, p, clearance_m)) continue;
    const double d = (p - goal).norm();
    out.ok = true;
    out.moved = true;
    out.position = p;
    out.moved_m = d;
    std::ostringstream why;
    why.precision(2);
    why << std::fixed << asked << ": moved " << d << " m to the nearest free point " << point(p);
    out.why = why.str();
    return out;
  }
  std::ostringstream why;
  why.precision(2);
  why << std::fixed << asked << ", and no free point lies within " << radius_m
      << " m of it (arbiter.goal_relocate_radius_m)";
  out.why = why.str();
  return out;
}

}  // namespace mmh::arbiter
