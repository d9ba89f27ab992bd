#include "mmh/som/clearance_cost.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace mmh::som {

namespace {

// Probe directions with their step lengths in cells: the six axes and the four horizontal
// diagonals (trunks are vertical, so the horizontal clearance is what a gap between them offers).
struct Probe {
  Eigen::Vector3i direction;
  double step_cells;
};
const double kDiagonal = std::sqrt(2.0);
const std::array<Probe, 10> kProbes = {{{{1, 0, 0}, 1.0},
                                        {{-1, 0, 0}, 1.0},
                                        {{0, 1, 0}, 1.0},
                                        {{0, -1, 0}, 1.0},
                                        {{0, 0, 1}, 1.0},
                                        {{0, 0, -1}, 1.0},
                                        {{1, 1, 0}, kDiagonal},
                                        {{1, -1, 0}, kDiagonal},
                                        {{-1, 1, 0}, kDiagonal},
                                        {{-1, -1, 0}, kDiagonal}}};

}  // namespace

double ClearanceCost::cellCost(const VoxelGrid& grid, const Eigen::Vector3i& local,
                               const ClearanceCostParams& params) {
  const double res = grid.resolution();
  // The clearance of a cell is the distance from its centre to the near face of the first
  // blocked cell met: a blocked neighbour leaves half a cell. Probes go out a step at a time in
  // all directions together, so the first hit (on an axis before a diagonal at the same step)
  // ends the search for most cells near obstacles.
  const int max_steps = static_cast<int>(std::ceil(params.width_m / res + 0.5));
  double clearance = params.width_m;
  for (int k = 1; k <= max_steps; ++k) {
    for (const Probe& probe : kProbes) {
      const double reach = (k * probe.step_cells - 0.5) * res;
      if (reach < clearance && grid.isBlocked(local + k * probe.direction)) clearance = reach;
    }
    if ((k + 0.5) * res >= clearance) break;  // no farther step can come nearer
  }
  return params.cost_cells * std::max(0.0, 1.0 - clearance / params.width_m);
}

void ClearanceCost::reserve(int64_t num_cells) {
  if (static_cast<int64_t>(memo_.size()) == num_cells) return;
  memo_.assign(num_cells, 0);
  generation_ = 0;
}

std::function<double(const Eigen::Vector3i&, int64_t)> ClearanceCost::forGrid(
    const VoxelGrid& grid, const Eigen::Vector3d& start, const ClearanceCostParams& params) {
  if (params.cost_cells <= 0.0 || params.width_m <= 0.0) return {};
  reserve(grid.numCells());
  if (++generation_ == 0) {  // wrapped: stale entries could look fresh
    std::fill(memo_.begin(), memo_.end(), uint16_t{0});
    generation_ = 1;
  }
  const uint16_t stamp = static_cast<uint16_t>(generation_) << 8;
  const double free_radius_sq = params.free_radius_m * params.free_radius_m;
  return [this, &grid, start, params, stamp, free_radius_sq](const Eigen::Vector3i& local,
                                                             int64_t index) {
    if ((grid.centerOfLocal(local) - start).squaredNorm() < free_radius_sq) return 0.0;
    uint16_t& entry = memo_[index];
    if ((entry & 0xff00) != stamp) {
      const double fraction = cellCost(grid, local, params) / params.cost_cells;
      entry = stamp | static_cast<uint16_t>(std::lround(255.0 * fraction));
    }
    return params.cost_cells * (entry & 0xff) / 255.0;
  };
}

}  // namespace mmh::som
