#include "mmh/eam/guide_search.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace mmh::eam {

bool inSlot(const VoxelGrid& grid, const Eigen::Vector3i& c, int reach, int diag_reach) {
  // Walks linear indices (this runs for every cell A* touches when slots cost extra).
  const Eigen::Vector3i& size = grid.size();
  const int64_t sx = 1, sy = size.x(), sz = static_cast<int64_t>(size.x()) * size.y();
  const int axes[5][4] = {{1, 0, 0, reach},
                          {0, 1, 0, reach},
                          {0, 0, 1, reach},
                          {1, 1, 0, diag_reach},
                          {1, -1, 0, diag_reach}};
  if (!grid.inWindow(c)) return false;
  const int64_t base = grid.linearIndex(c);
  const uint16_t* blocked = grid.blockedCounts();
  // A cell at least the probes' reach inside the window needs no window test per probe.
  const int far = std::max(reach, diag_reach);
  const bool interior = (c.array() >= far).all() && (c.array() < size.array() - far).all();
  auto blocked_along = [&](const int* a, int sign) {
    const int64_t step = sign * (a[0] * sx + a[1] * sy + a[2] * sz);
    for (int k = 1; k <= a[3]; ++k) {
      if (!interior && !grid.inWindow(c + sign * k * Eigen::Vector3i(a[0], a[1], a[2])))
        return false;  // unknown beyond the window: free
      if (blocked[base + k * step] > 0) return true;
    }
    return false;
  };
  for (const auto& a : axes) {
    if (blocked_along(a, +1) && blocked_along(a, -1)) return true;
  }
  return false;
}

void GuideSearch::prepare(const VoxelGrid& grid) {
  if (!grid.valid()) return;
  if (static_cast<int64_t>(slot_memo_.size()) != grid.numCells())
    slot_memo_.assign(grid.numCells(), 0);
  astar_.reserve(grid.numCells());
}

AStarResult GuideSearch::find(const VoxelGrid& grid, const Eigen::Vector3d& from,
                              const Eigen::Vector3d& goal, double z_lo, double z_hi,
                              bool avoid_slots, double slot_width_m, GuideStats* stats) {
  const EamParams& P = params_;
  AStarOptions band;
  band.max_expansions = P.astar_max_expansions;
  band.min_bound = P.geofence_min;
  band.max_bound = P.geofence_max;
  band.start_escape_radius_m = P.start_escape_radius_m;
  band.heuristic_weight = P.astar_heuristic_weight;
  // First the voxel layers the stretch occupies (a detour around a new obstacle is almost
  // always sideways, and a thin slab keeps A* from fanning out over every layer) within a box
  // around it (a blocked way does not send the search over the whole window); then the band.
  AStarOptions slab = band;
  const Eigen::Vector3d box_lo = from.cwiseMin(goal).array() - P.astar_box_margin_m;
  const Eigen::Vector3d box_hi = from.cwiseMax(goal).array() + P.astar_box_margin_m;
  slab.min_bound.head<2>() = slab.min_bound.head<2>().cwiseMax(box_lo.head<2>());
  slab.max_bound.head<2>() = slab.max_bound.head<2>().cwiseMin(box_hi.head<2>());
  const double res = grid.resolution();
  const double layer_lo = (std::floor(z_lo / res) + 0.5) * res - 0.25 * res;
  const double layer_hi = (std::floor(z_hi / res) + 0.5) * res + 0.25 * res;
  slab.min_bound.z() = std::max(P.geofence_min.z(), layer_lo - P.astar_slab_margin_m);
  slab.max_bound.z() = std::min(P.geofence_max.z(), layer_hi + P.astar_slab_margin_m);

  const int reach = std::max(1, static_cast<int>(std::lround(slot_width_m / res)));
  const int diag_reach =
      std::max(1, static_cast<int>(std::lround(slot_width_m / (std::sqrt(2.0) * res))));
  auto slot_cost = [&](const Eigen::Vector3i& c, int64_t idx) {
    int8_t& m = slot_memo_[idx];
    if (m == 0) {
      m = inSlot(grid, c, reach, diag_reach) ? 1 : 2;
      slot_touched_.push_back(idx);
    }
    return m == 1 ? P.astar_slot_cost : 0.0;
  };
  auto search = [&](AStarOptions o, bool with_slot_cost) {
    if (with_slot_cost) {
      if (static_cast<int64_t>(slot_memo_.size()) != grid.numCells())
        slot_memo_.assign(grid.numCells(), 0);
      o.extra_step_cost = slot_cost;
    }
    const auto t0 = std::chrono::steady_clock::now();
    AStarResult found = astar_.search(grid, from, goal, o);
    stats->us +=
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    ++stats->calls;
    stats->expansions += found.expansions;
    for (int64_t idx : slot_touched_) slot_memo_[idx] = 0;
    slot_touched_.clear();
    return found;
  };

  const bool slot_cost_first = avoid_slots && P.astar_slot_cost > 0.0;
  bool in_slab = true;
  AStarResult path = search(slab, slot_cost_first);
  if (!path.ok() && path.status != AStarResult::Status::kOutOfWindow) {
    // No way within the box: the same layers over the whole window (a long detour stays cheap
    // in a thin slab), and only then every layer of the band.
    slab.min_bound.head<2>() = band.min_bound.head<2>();
    slab.max_bound.head<2>() = band.max_bound.head<2>();
    path = search(slab, slot_cost_first);
  }
  if (!path.ok() && path.status != AStarResult::Status::kOutOfWindow) {
    in_slab = false;
    path = search(band, slot_cost_first);
  }
  if (!path.ok()) return path;
  if (!slot_cost_first && P.astar_slot_cost > 0.0) {
    // A shortest path threads gaps one or two voxels wide that no smooth curve at speed can
    // follow; if this one does, search again with the slot cost, which takes a wider way when
    // there is one within a few voxels of detour.
    bool threads_slot = false;
    for (size_t k = 1; k + 1 < path.path.size() && !threads_slot; ++k) {
      threads_slot = inSlot(grid, grid.localIndexOf(path.path[k]), reach, diag_reach);
    }
    if (threads_slot) {
      AStarResult wide = search(in_slab ? slab : band, true);
      if (wide.ok()) path = std::move(wide);
    }
  }
  if (in_slab) {
    // Within the slab, the altitudes of the cell centres (a voxel apart) are quantisation, not
    // intent: ramp them between the end points so that they do not tilt the repulsive
    // directions of points the guide passes close to.
    const double total = pathLength(path.path);
    double along = 0.0;
    for (size_t k = 1; k + 1 < path.path.size(); ++k) {
      along += (path.path[k] - path.path[k - 1]).norm();
      path.path[k].z() = from.z() + (goal.z() - from.z()) * (total > 0.0 ? along / total : 0.0);
    }
  }
  return path;
}

}  // namespace mmh::eam
