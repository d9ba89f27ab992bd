#include "mmh/common/grid_astar.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <queue>

#include "mmh/common/collision_check.hpp"

namespace mmh {
namespace {

constexpr uint32_t kClosedBit = 0x80000000u;

// Exact cost of the shortest 26-connected path in free space (in cells).
double octileDistance(const Eigen::Vector3i& a, const Eigen::Vector3i& b) {
  std::array<int, 3> d = {std::abs(a.x() - b.x()), std::abs(a.y() - b.y()),
                          std::abs(a.z() - b.z())};
  std::sort(d.begin(), d.end());  // d[0] <= d[1] <= d[2]
  return d[2] + (std::sqrt(2.0) - 1.0) * d[1] + (std::sqrt(3.0) - std::sqrt(2.0)) * d[0];
}

struct OpenEntry {
  float f;
  int32_t index;
  bool operator>(const OpenEntry& o) const { return f > o.f; }
};

}  // namespace

const char* toString(AStarResult::Status status) {
  switch (status) {
    case AStarResult::Status::kFound:
      return "found";
    case AStarResult::Status::kStartBlocked:
      return "start blocked";
    case AStarResult::Status::kGoalBlocked:
      return "goal blocked";
    case AStarResult::Status::kOutOfWindow:
      return "start or goal outside the map window";
    case AStarResult::Status::kNoPath:
      return "no path";
    case AStarResult::Status::kBudgetExceeded:
      return "node budget exceeded";
  }
  return "?";
}

AStarResult GridAStar::search(const VoxelGrid& grid, const Eigen::Vector3d& start,
                              const Eigen::Vector3d& goal, const AStarOptions& options) {
  AStarResult result;
  const Eigen::Vector3i s = grid.localIndexOf(start);
  const Eigen::Vector3i g = grid.localIndexOf(goal);
  if (!grid.inWindow(s) || !grid.inWindow(g) || !start.allFinite() || !goal.allFinite()) {
    result.status = AStarResult::Status::kOutOfWindow;
    return result;
  }
  // Cell-index bounds of the allowed box, intersected with the window.
  const double res = grid.resolution();
  Eigen::Vector3i lo, hi;
  for (int i = 0; i < 3; ++i) {
    // Clamp in floating point first: the default bounds are far outside int range.
    const double first = std::ceil(options.min_bound[i] / res - 0.5) - grid.originIndex()[i];
    const double last = std::floor(options.max_bound[i] / res - 0.5) - grid.originIndex()[i];
    lo[i] = static_cast<int>(std::clamp(first, 0.0, double(grid.size()[i])));
    hi[i] = static_cast<int>(std::clamp(last, -1.0, double(grid.size()[i] - 1)));
  }
  auto in_bounds = [&](const Eigen::Vector3i& c) {
    return (c.array() >= lo.array()).all() && (c.array() <= hi.array()).all();
  };
  const double escape_cells = options.start_escape_radius_m / res;
  auto traversable = [&](const Eigen::Vector3i& c, int64_t idx) {
    const Occupancy occ = grid.atLinear(idx);
    if (occ == Occupancy::kOccupied) return false;
    if (!options.unknown_is_free && occ == Occupancy::kUnknown) return false;
    if (!grid.isBlockedLinear(idx)) return true;
    return escape_cells > 0.0 && (c - s).cast<double>().norm() <= escape_cells;
  };
  const int64_t s_idx = grid.linearIndex(s), g_idx = grid.linearIndex(g);
  if (!traversable(s, s_idx)) {
    result.status = AStarResult::Status::kStartBlocked;
    return result;
  }
  if (grid.isBlockedLinear(g_idx) || !traversable(g, g_idx) || !in_bounds(g)) {
    result.status = AStarResult::Status::kGoalBlocked;
    return result;
  }

  const int64_t n = grid.numCells();
  if (static_cast<int64_t>(stamp_.size()) != n) {
    g_cost_.assign(n, 0.f);
    parent_.assign(n, -1);
    stamp_.assign(n, 0);
    generation_ = 0;
  }
  if (++generation_ >= kClosedBit) {
    std::fill(stamp_.begin(), stamp_.end(), 0);
    generation_ = 1;
  }
  auto seen = [&](int64_t i) { return (stamp_[i] & ~kClosedBit) == generation_; };
  auto closed = [&](int64_t i) { return stamp_[i] == (generation_ | kClosedBit); };

  // Slight tie-breaking towards the goal keeps the search from fanning out on plateaus.
  const double h_weight = std::max(1.0 + 1e-3, options.heuristic_weight);
  std::priority_queue<OpenEntry, std::vector<OpenEntry>, std::greater<OpenEntry>> open;
  stamp_[s_idx] = generation_;
  g_cost_[s_idx] = 0.f;
  parent_[s_idx] = -1;
  open.push({static_cast<float>(h_weight * octileDistance(s, g)), static_cast<int32_t>(s_idx)});

  bool found = false;
  while (!open.empty()) {
    const OpenEntry top = open.top();
    open.pop();
    const int64_t cur = top.index;
    if (closed(cur)) continue;
    stamp_[cur] = generation_ | kClosedBit;
    if (cur == g_idx) {
      found = true;
      break;
    }
    if (++result.expansions > options.max_expansions) {
      result.status = AStarResult::Status::kBudgetExceeded;
      return result;
    }
    const Eigen::Vector3i c = grid.localFromLinear(cur);
    const float gc = g_cost_[cur];
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          if (dx == 0 && dy == 0 && dz == 0) continue;
          const Eigen::Vector3i nb = c + Eigen::Vector3i(dx, dy, dz);
          if (!in_bounds(nb)) continue;
          const int64_t ni = grid.linearIndex(nb);
          if (closed(ni) || !traversable(nb, ni)) continue;
          float step = static_cast<float>(std::sqrt(double(dx * dx + dy * dy + dz * dz)));
          if (options.extra_step_cost) step += static_cast<float>(options.extra_step_cost(nb, ni));
          const float ng = gc + step;
          if (seen(ni) && g_cost_[ni] <= ng) continue;
          stamp_[ni] = generation_;
          g_cost_[ni] = ng;
          parent_[ni] = static_cast<int32_t>(cur);
          open.push({static_cast<float>(ng + h_weight * octileDistance(nb, g)),
                     static_cast<int32_t>(ni)});
        }
      }
    }
  }
  if (!found) {
    result.status = AStarResult::Status::kNoPath;
    return result;
  }
  std::vector<Eigen::Vector3d> reversed;
  for (int64_t i = g_idx; i >= 0; i = parent_[i]) {
    reversed.push_back(grid.centerOfLocal(grid.localFromLinear(i)));
    if (i == s_idx) break;
  }
  result.path.assign(reversed.rbegin(), reversed.rend());
  result.path.front() = start;
  if (result.path.size() == 1)
    result.path.push_back(goal);
  else
    result.path.back() = goal;
  result.status = AStarResult::Status::kFound;
  return result;
}

std::vector<Eigen::Vector3d> shortenPath(const VoxelGrid& grid,
                                         const std::vector<Eigen::Vector3d>& path) {
  if (path.size() <= 2) return path;
  std::vector<Eigen::Vector3d> out{path.front()};
  size_t anchor = 0;
  while (anchor + 1 < path.size()) {
    // Walk forward while the straight segment from the anchor stays free; the adjacent point
    // is always reachable (A* moved there).
    size_t next = anchor + 1;
    while (next + 1 < path.size() && isSegmentFree(grid, path[anchor], path[next + 1])) ++next;
    out.push_back(path[next]);
    anchor = next;
  }
  return out;
}

double pathLength(const std::vector<Eigen::Vector3d>& path) {
  double l = 0.0;
  for (size_t i = 1; i < path.size(); ++i) l += (path[i] - path[i - 1]).norm();
  return l;
}

}  // namespace mmh
