// Cells of a regular grid pierced by a ray, in order (Amanatides & Woo), for the simulator's
// voxel ray casting. Private to mmh_sim.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <limits>

namespace mmh::sim::detail {

// Visits the cells of edge `cell` met by origin + t dir for t in [t0, t1], in order of t.
// visit(const Eigen::Vector3i& cell_index, double t_in, double t_out) returns false to stop.
template <class F>
void traverseCells(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t0, double t1,
                   double cell, F&& visit) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d p = origin + t0 * dir;
  Eigen::Vector3i c;
  Eigen::Vector3i step;
  Eigen::Vector3d t_max, t_delta;
  for (int i = 0; i < 3; ++i) {
    c[i] = static_cast<int>(std::floor(p[i] / cell));
    if (dir[i] > 0.0) {
      step[i] = 1;
      t_max[i] = t0 + ((c[i] + 1) * cell - p[i]) / dir[i];
      t_delta[i] = cell / dir[i];
    } else if (dir[i] < 0.0) {
      step[i] = -1;
      t_max[i] = t0 + (c[i] * cell - p[i]) / dir[i];
      t_delta[i] = -cell / dir[i];
    } else {
      step[i] = 0;
      t_max[i] = kInf;
      t_delta[i] = kInf;
    }
  }
  double t_in = t0;
  for (;;) {
    int axis = 0;
    if (t_max[1] < t_max[axis]) axis = 1;
    if (t_max[2] < t_max[axis]) axis = 2;
    const double t_out = std::min(t_max[axis], t1);
    if (!visit(static_cast<const Eigen::Vector3i&>(c), t_in, t_out)) return;
    if (t_max[axis] >= t1) return;
    t_in = t_max[axis];
    c[axis] += step[axis];
    t_max[axis] += t_delta[axis];
  }
}

}  // namespace mmh::sim::detail
