#include "mmh/common/grid_astar.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>

#include "mmh/common/collision_check.hpp"

namespace mmh {
namespace {

constexpr uint32_t kClosedBit = 0x80000000u;

// Exact cost of the shortest 26-connected path in free space (in cells).
double octileDistance(const Eigen::Vector3i& a, const Eigen::Vector3i& b) {
  const int x = std::abs(a.x() - b.x()), y = std::abs(a.y() - b.y()), z = std::abs(a.z() - b.z());
  const int hi = std::max({x, y, z}), lo = std::min({x, y, z}), mid = x + y + z - hi - lo;
  return hi + (std::sqrt(2.0) - 1.0) * mid + (std::sqrt(3.0) - std::sqrt(2.0)) * lo;
}

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

void GridAStar::reserve(int64_t num_cells) {
  if (static_cast<int64_t>(cells_.size()) == num_cells) return;
  cells_.assign(num_cells, CellState{});
  generation_ = 0;
  open_.reserve(1 << 16);
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
  // These two run for every neighbour: inlined (GCC otherwise calls them from this long function).
  auto in_bounds = [&](const Eigen::Vector3i& c) __attribute__((always_inline)) {
    return c.x() >= lo.x() && c.y() >= lo.y() && c.z() >= lo.z() && c.x() <= hi.x() &&
           c.y() <= hi.y() && c.z() <= hi.z();
  };
  const double escape_cells = options.start_escape_radius_m / res;
  auto escapes_start = [&](const Eigen::Vector3i& c) {
    if (!(escape_cells > 0.0 && (c - s).cast<double>().norm() <= escape_cells)) return false;
    return c == s || keepsEscapeDistance(grid, grid.centerOfLocal(c),
                                         options.start_escape_min_distance_m, 0.0);
  };
  auto traversable = [&](const Eigen::Vector3i& c, int64_t idx) __attribute__((always_inline)) {
    const Occupancy occ = grid.atLinear(idx);
    if (occ == Occupancy::kOccupied) return false;
    if (!options.unknown_is_free && occ == Occupancy::kUnknown) return false;
    return !grid.isBlockedLinear(idx) || escapes_start(c);
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

  reserve(grid.numCells());
  if (++generation_ >= kClosedBit) {
    for (CellState& c : cells_) c.stamp = 0;
    generation_ = 1;
  }
  auto closed = [&](int64_t i) { return cells_[i].stamp == (generation_ | kClosedBit); };

  // Slight tie-breaking towards the goal keeps the search from fanning out on plateaus.
  const double h_weight = std::max(1.0, options.heuristic_weight) * (1.0 + 1e-3);
  // The open list is a binary heap in a vector kept across searches (no reallocation).
  std::vector<GridAStar::OpenEntry>& open = open_;
  open.clear();
  const auto heap_order = std::greater<GridAStar::OpenEntry>();
  auto push = [&](float f, int64_t index) {
    open.push_back({f, static_cast<int32_t>(index)});
    std::push_heap(open.begin(), open.end(), heap_order);
  };
  cells_[s_idx] = {0.f, -1, generation_, 0.f};
  push(static_cast<float>(h_weight * octileDistance(s, g)), s_idx);

  // The 26 neighbour offsets with their step lengths.
  struct Neighbour {
    Eigen::Vector3i d;
    int64_t delta;
    float step;
  };
  std::array<Neighbour, 26> neighbours;
  int count = 0;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0 && dz == 0) continue;
        neighbours[count++] = {Eigen::Vector3i(dx, dy, dz),
                               dx + int64_t{grid.size().x()} * (dy + int64_t{grid.size().y()} * dz),
                               static_cast<float>(std::sqrt(double(dx * dx + dy * dy + dz * dz)))};
      }

  bool found = false;
  while (!open.empty()) {
    std::pop_heap(open.begin(), open.end(), heap_order);
    const OpenEntry top = open.back();
    open.pop_back();
    const int64_t cur = top.index;
    if (closed(cur)) continue;
    cells_[cur].stamp = generation_ | kClosedBit;
    if (cur == g_idx) {
      found = true;
      break;
    }
    if (++result.expansions > options.max_expansions) {
      result.status = AStarResult::Status::kBudgetExceeded;
      return result;
    }
    const Eigen::Vector3i c = grid.localFromLinear(cur);
    const float gc = cells_[cur].g;
    for (const Neighbour& n : neighbours) {
      const Eigen::Vector3i nb = c + n.d;
      if (!in_bounds(nb)) continue;
      const int64_t ni = cur + n.delta;
      if (closed(ni) || !traversable(nb, ni)) continue;
      CellState& cell = cells_[ni];
      if ((cell.stamp & ~kClosedBit) != generation_) {  // first reached: not yet on the open list
        const float extra =
            options.extra_step_cost ? static_cast<float>(options.extra_step_cost(nb, ni)) : 0.f;
        cell = {std::numeric_limits<float>::infinity(), -1, generation_, extra};
      }
      const float ng = gc + (n.step + cell.extra);  // extra is 0 without an extra cost
      if (cell.g <= ng) continue;
      cell.g = ng;
      cell.parent = static_cast<int32_t>(cur);
      push(static_cast<float>(ng + h_weight * octileDistance(nb, g)), ni);
    }
  }
  if (!found) {
    result.status = AStarResult::Status::kNoPath;
    return result;
  }
  std::vector<Eigen::Vector3d> reversed;
  for (int64_t i = g_idx; i >= 0; i = cells_[i].parent) {
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

std::vector<Eigen::Vector3d> shortenPath(
    const VoxelGrid& grid, const std::vector<Eigen::Vector3d>& path,
    const std::function<bool(const Eigen::Vector3d&)>& keep_out) {
  if (path.size() <= 2) return path;
  std::vector<Eigen::Vector3d> out{path.front()};
  size_t anchor = 0;
  while (anchor + 1 < path.size()) {
    // Walk forward while the straight segment from the anchor stays free; the adjacent point
    // is always reachable (A* moved there).
    size_t next = anchor + 1;
    while (next + 1 < path.size() &&
           isSegmentFree(grid, path[anchor], path[next + 1], CollisionLayer::kInflated, keep_out))
      ++next;
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
