#include "mmh/common/narrow_space.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "cell_lookup.hpp"

namespace mmh {

NarrowSpaceProbe::NarrowSpaceProbe(const VoxelGrid& grid, double probe_dist_m) : grid_(grid) {
  // The same accumulated sample distances as a plain `for (s = step; s <= dist; s += step)`.
  const double step = 0.5 * grid.resolution();
  for (double s = step; s <= probe_dist_m + 1e-9; s += step) offsets_.push_back(s);
}

// Window cell indices along axis c of the samples pc + s * nc of a probe, from the memo when an
// earlier probe had the same coordinate and direction: a horizontal sensing ray keeps the height
// and the vertical normal of every sample pair, so its vertical probes repeat from pair to pair.
const int* NarrowSpaceProbe::axisCells(int c, double pc, double nc) const {
  AxisMemo* slots = memo_[c];
  for (int i = 0; i < kMemoSlots; ++i) {
    if (slots[i].pc == pc && slots[i].nc == nc) return slots[i].cells.data();
  }
  AxisMemo& slot = slots[next_slot_[c]];
  next_slot_[c] = (next_slot_[c] + 1) % kMemoSlots;
  slot.pc = pc;
  slot.nc = nc;
  const double res = grid_.resolution();
  const int origin = grid_.originIndex()[c];
  const int count = static_cast<int>(offsets_.size());
  const double* offsets = offsets_.data();
  int* cells = slot.cells.data();
  for (int k = 0; k < count; ++k) {
    const double q = (pc + offsets[k] * nc) / res;  // the division of VoxelGrid::globalIndexOf
    const int t = static_cast<int>(q);
    cells[k] = t - (q < t ? 1 : 0) - origin;
  }
  return slot.cells.data();
}

// Occupied cell within the probe distance of p along unit direction n? The samples are
// p + s * n for each offset s, each looked up exactly like VoxelGrid::atPoint (floor of the
// division by the resolution). An axis along which n is zero keeps its coordinate
// (p_c + s * 0 == p_c), so its cell index is computed once; probes along the vertical or in the
// horizontal plane then vary only one or two coordinates. The cell indices of a probe are computed
// first (axisCells), then looked up.
bool NarrowSpaceProbe::probeHits(const Eigen::Vector3d& p, const Eigen::Vector3d& n) const {
  const detail::CellLookup cells(grid_);
  const int count = static_cast<int>(offsets_.size());
  const double res = grid_.resolution();
  // The batch path converts quotients to int without range checks: only for probes well inside
  // the int range (the probe is a segment, so its end points bound every sample).
  const double reach = offsets_.empty() ? 0.0 : offsets_.back();
  const bool batch = count <= kMaxBatch && (p.cwiseAbs().array() < 1e8 * res).all() &&
                     ((p + reach * n).cwiseAbs().array() < 1e8 * res).all();
  int local[3][kMaxBatch];
  bool varies[3];
  for (int c = 0; c < 3; ++c) {
    varies[c] = n[c] != 0.0;
    if (varies[c]) continue;
    const int fixed = cells.floorIndex(p[c]) - cells.origin()[c];
    if (fixed < 0 || fixed >= cells.size()[c]) return false;  // the whole probe is outside
    if (batch) std::fill_n(local[c], count, fixed);
    local[c][0] = fixed;
  }
  const int64_t sy = cells.size().x(), sz = sy * cells.size().y();
  if (!batch) {
    for (const double s : offsets_) {
      int cell[3];
      bool inside = true;
      for (int c = 0; c < 3; ++c) {
        cell[c] = varies[c] ? cells.floorIndex(p[c] + s * n[c]) - cells.origin()[c] : local[c][0];
        inside = inside && cell[c] >= 0 && cell[c] < cells.size()[c];
      }
      if (inside && cells.occupiedLinear(cell[0] + cell[1] * sy + cell[2] * sz)) return true;
    }
    return false;
  }
  const int* axis_cells[3] = {local[0], local[1], local[2]};
  for (int c = 0; c < 3; ++c) {
    if (varies[c]) axis_cells[c] = axisCells(c, p[c], n[c]);
  }
  const Eigen::Vector3i& size = cells.size();
  for (int k = 0; k < count; ++k) {
    const int x = axis_cells[0][k], y = axis_cells[1][k], z = axis_cells[2][k];
    // Unsigned compares fold the >= 0 and < size tests.
    if (static_cast<unsigned>(x) < static_cast<unsigned>(size.x()) &&
        static_cast<unsigned>(y) < static_cast<unsigned>(size.y()) &&
        static_cast<unsigned>(z) < static_cast<unsigned>(size.z()) &&
        cells.occupiedLinear(x + y * sy + z * sz))
      return true;
  }
  return false;
}

bool NarrowSpaceProbe::bothSidesBlocked(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
  // Without an occupied cell no probe can hit.
  if (grid_.numOccupied() == 0 || !grid_.valid()) return false;
  Eigen::Vector3d dir = b - a;
  if (dir.norm() < 1e-9) return false;
  dir.normalize();
  // Horizontal normal; for a vertical segment any horizontal direction will do.
  Eigen::Vector3d left = Eigen::Vector3d::UnitZ().cross(dir);
  if (left.norm() < 1e-6) left = Eigen::Vector3d::UnitY();
  left.normalize();
  const Eigen::Vector3d up = dir.cross(left).normalized();
  const Eigen::Vector3d mid = 0.5 * (a + b);
  if (probeHits(mid, left) && probeHits(mid, -left)) return true;
  return probeHits(mid, up) && probeHits(mid, -up);
}

bool bothSidesBlocked(const VoxelGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                      double probe_dist_m) {
  return NarrowSpaceProbe(grid, probe_dist_m).bothSidesBlocked(a, b);
}

bool isPathNarrow(const VoxelGrid& grid, const std::vector<Eigen::Vector3d>& path,
                  double probe_dist_m, Eigen::Vector3d* where) {
  const NarrowSpaceProbe probe(grid, probe_dist_m);
  const double step = grid.resolution();
  for (size_t i = 1; i < path.size(); ++i) {
    const Eigen::Vector3d a = path[i - 1], b = path[i];
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d p0 = a + (b - a) * (double(k) / n);
      const Eigen::Vector3d p1 = a + (b - a) * (double(k + 1) / n);
      if (probe.bothSidesBlocked(p0, p1)) {
        if (where) *where = 0.5 * (p0 + p1);
        return true;
      }
    }
  }
  return false;
}

}  // namespace mmh
