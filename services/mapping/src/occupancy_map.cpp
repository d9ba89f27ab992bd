#include "mmh/mapping/occupancy_map.hpp"

#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

namespace mmh::mapping {
namespace {

// OctoMap keys are global voxel indices shifted by this (16-level tree).
constexpr int kKeyOffset = 32768;

octomap::OcTreeKey toKey(const Eigen::Vector3i& g) {
  return octomap::OcTreeKey(static_cast<octomap::key_type>(g.x() + kKeyOffset),
                            static_cast<octomap::key_type>(g.y() + kKeyOffset),
                            static_cast<octomap::key_type>(g.z() + kKeyOffset));
}

int64_t pack(const Eigen::Vector3i& g) {
  return (static_cast<int64_t>(g.x() + kKeyOffset) << 32) |
         (static_cast<int64_t>(g.y() + kKeyOffset) << 16) |
         static_cast<int64_t>(g.z() + kKeyOffset);
}

Eigen::Vector3i unpack(int64_t v) {
  return Eigen::Vector3i(static_cast<int>((v >> 32) & 0xffff) - kKeyOffset,
                         static_cast<int>((v >> 16) & 0xffff) - kKeyOffset,
                         static_cast<int>(v & 0xffff) - kKeyOffset);
}

int positiveMod(int a, int n) {
  const int m = a % n;
  return m < 0 ? m + n : m;
}

bool boxesMeet(const Eigen::Vector3i& alo, const Eigen::Vector3i& ahi, const Eigen::Vector3i& blo,
               const Eigen::Vector3i& bhi) {  // inclusive corners
  return (alo.array() <= bhi.array()).all() && (blo.array() <= ahi.array()).all();
}

}  // namespace

// OcTree with pruning restricted to the part outside the window (the window's leaves are
// referenced by the ring buffer and must not be deleted).
struct OccupancyMap::Tree : public octomap::OcTree {
  using octomap::OcTree::OcTree;

  // Prunes every subtree that lies outside [keep_lo, keep_hi] and meets [region_lo, region_hi]
  // (global voxel indices, inclusive).
  void pruneOutside(const Eigen::Vector3i& keep_lo, const Eigen::Vector3i& keep_hi,
                    const Eigen::Vector3i& region_lo, const Eigen::Vector3i& region_hi) {
    if (this->root) {
      recurse(this->root, 0, Eigen::Vector3i::Constant(-kKeyOffset), keep_lo, keep_hi, region_lo,
              region_hi);
    }
  }

 private:
  bool pruneAll(octomap::OcTreeNode* node) {
    if (!this->nodeHasChildren(node)) return true;
    bool children_are_leaves = true;
    for (unsigned i = 0; i < 8; ++i) {
      if (this->nodeChildExists(node, i) && !pruneAll(this->getNodeChild(node, i))) {
        children_are_leaves = false;
      }
    }
    return children_are_leaves && this->pruneNode(node);
  }

  void recurse(octomap::OcTreeNode* node, unsigned depth, const Eigen::Vector3i& base,
               const Eigen::Vector3i& keep_lo, const Eigen::Vector3i& keep_hi,
               const Eigen::Vector3i& region_lo, const Eigen::Vector3i& region_hi) {
    const int span = 1 << (this->tree_depth - depth);
    const Eigen::Vector3i last = base + Eigen::Vector3i::Constant(span - 1);
    if (!boxesMeet(base, last, region_lo, region_hi)) return;
    // Entirely inside the window: nothing to prune there.
    if ((base.array() >= keep_lo.array()).all() && (last.array() <= keep_hi.array()).all()) return;
    if (!boxesMeet(base, last, keep_lo, keep_hi)) {
      pruneAll(node);
      return;
    }
    if (depth == this->tree_depth) return;
    const int half = span / 2;
    for (unsigned i = 0; i < 8; ++i) {
      if (!this->nodeChildExists(node, i)) continue;
      const Eigen::Vector3i child_base =
          base + Eigen::Vector3i((i & 1) ? half : 0, (i & 2) ? half : 0, (i & 4) ? half : 0);
      recurse(this->getNodeChild(node, i), depth + 1, child_base, keep_lo, keep_hi, region_lo,
              region_hi);
    }
  }
};

OccupancyMap::OccupancyMap(const MappingParams& params)
    : params_(params),
      res_(params.resolution_m),
      log_hit_(octomap::logodds(params.prob_hit)),
      log_miss_(octomap::logodds(params.prob_miss)),
      clamp_min_(octomap::logodds(params.clamp_min)),
      clamp_max_(octomap::logodds(params.clamp_max)),
      occ_threshold_(octomap::logodds(params.occupancy_threshold)),
      tree_(std::make_unique<Tree>(params.resolution_m)) {
  tree_->setProbHit(params.prob_hit);
  tree_->setProbMiss(params.prob_miss);
  tree_->setClampingThresMin(params.clamp_min);
  tree_->setClampingThresMax(params.clamp_max);
  tree_->setOccupancyThres(params.occupancy_threshold);
  size_ = params.windowCells();
  // The ring is the window rounded up to whole bricks; the window's cells map to distinct slots.
  bricks_ = (size_.array() + 7) / 8;
  ring_ = bricks_ * 8;
  const size_t n = static_cast<size_t>(ring_.x()) * ring_.y() * ring_.z();
  node_.assign(n, nullptr);
  log_odds_.assign(n, std::numeric_limits<float>::quiet_NaN());
  stamp_.assign(n, 0);
  dirty_.assign(n, 0);
}

OccupancyMap::~OccupancyMap() = default;

const octomap::OcTree& OccupancyMap::octree() const {
  return *tree_;
}

size_t OccupancyMap::octreeLeaves() const {
  return tree_->getNumLeafNodes();
}

int64_t OccupancyMap::ringIndex(const Eigen::Vector3i& g) const {
  return ringSlot(positiveMod(g.x(), ring_.x()), positiveMod(g.y(), ring_.y()),
                  positiveMod(g.z(), ring_.z()));
}

void OccupancyMap::resetBox(const Eigen::Vector3i& lo, const Eigen::Vector3i& hi) {
  const float unknown = std::numeric_limits<float>::quiet_NaN();
  for (int z = lo.z(); z < hi.z(); ++z) {
    const int rz = positiveMod(z, ring_.z());
    for (int y = lo.y(); y < hi.y(); ++y) {
      const int ry = positiveMod(y, ring_.y());
      int rx = positiveMod(lo.x(), ring_.x());
      for (int x = lo.x(); x < hi.x(); ++x) {
        const int64_t slot = ringSlot(rx, ry, rz);
        node_[slot] = nullptr;
        log_odds_[slot] = unknown;
        if (++rx == ring_.x()) rx = 0;
      }
    }
  }
}

void OccupancyMap::markChanged(const Eigen::Vector3i& g) {
  changed_.push_back(pack(g));
}

void OccupancyMap::setKnown(int64_t ring, const Eigen::Vector3i& g, float log_odds,
                            octomap::OcTreeNode* node) {
  log_odds_[ring] = log_odds;
  node_[ring] = node;
  states_[windowIndex(g)] = static_cast<uint8_t>(stateOf(log_odds));
  markChanged(g);
}

void OccupancyMap::loadBox(const Eigen::Vector3i& lo, const Eigen::Vector3i& hi) {
  if ((hi.array() <= lo.array()).any()) return;
  const unsigned depth = tree_->getTreeDepth();
  const Eigen::Vector3i last = hi - Eigen::Vector3i::Ones();
  for (auto it = tree_->begin_leafs_bbx(toKey(lo), toKey(last)), end = tree_->end_leafs_bbx();
       it != end; ++it) {
    const octomap::OcTreeKey k = it.getIndexKey();
    const int span = 1 << (depth - it.getDepth());
    const Eigen::Vector3i first(k[0] - kKeyOffset, k[1] - kKeyOffset, k[2] - kKeyOffset);
    const Eigen::Vector3i from = first.cwiseMax(lo);
    const Eigen::Vector3i to = (first + Eigen::Vector3i::Constant(span)).cwiseMin(hi);
    // A full-depth leaf is cached; a pruned (coarser) leaf gives its value to every cell and is
    // expanded by the first update that reaches one of them.
    octomap::OcTreeNode* node = span == 1 ? &(*it) : nullptr;
    const float value = it->getLogOdds();
    for (int z = from.z(); z < to.z(); ++z)
      for (int y = from.y(); y < to.y(); ++y)
        for (int x = from.x(); x < to.x(); ++x) {
          const Eigen::Vector3i g(x, y, z);
          setKnown(ringIndex(g), g, value, node);
        }
  }
}

bool OccupancyMap::followVehicle(const Eigen::Vector3d& position) {
  if (!position.allFinite()) return false;
  const Eigen::Vector3i centre_cell((position / res_).array().floor().cast<int>());
  // Keep the window inside the tree's key range (+-3.2 km at 0.1 m).
  const Eigen::Vector3i min_origin = Eigen::Vector3i::Constant(-kKeyOffset + 1);
  const Eigen::Vector3i max_origin = Eigen::Vector3i::Constant(kKeyOffset - 1) - size_;
  const Eigen::Vector3i wanted =
      (centre_cell - size_ / 2).cwiseMax(min_origin).cwiseMin(max_origin);
  if (!has_window_) {
    origin_ = wanted;
    has_window_ = true;
    states_.assign(static_cast<size_t>(size_.x()) * size_.y() * size_.z(), 0);
    region_lo_ = origin_;
    region_hi_ = origin_ + size_ - Eigen::Vector3i::Ones();
    loadBox(origin_, origin_ + size_);
    return true;
  }
  const Eigen::Vector3d centre = (origin_.cast<double>() + 0.5 * size_.cast<double>()) * res_;
  if (((position - centre).cwiseAbs().array() <= params_.window_recenter_m).all()) return false;
  if (wanted == origin_) return false;
  flush();  // cells about to leave must reach the tree
  const Eigen::Vector3i old = origin_;
  shiftStates(wanted - old);
  origin_ = wanted;
  moved_since_prune_ = true;
  region_lo_ = region_lo_.cwiseMin(origin_);
  region_hi_ = region_hi_.cwiseMax(origin_ + size_ - Eigen::Vector3i::Ones());
  const Eigen::Vector3i shift = wanted - old;
  if ((shift.cwiseAbs().array() >= size_.array()).any()) {
    std::fill(node_.begin(), node_.end(), nullptr);
    std::fill(log_odds_.begin(), log_odds_.end(), std::numeric_limits<float>::quiet_NaN());
    loadBox(origin_, origin_ + size_);
    return true;
  }
  // The cells that entered: up to three disjoint slabs. A slot may still hold a cell that left,
  // so the slots of entering cells are cleared first.
  const Eigen::Vector3i new_hi = origin_ + size_;
  Eigen::Vector3i lo = origin_, hi = new_hi;
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::Vector3i slab_lo = lo, slab_hi = hi;
    if (shift[axis] > 0) {
      slab_lo[axis] = old[axis] + size_[axis];
      slab_hi[axis] = new_hi[axis];
    } else if (shift[axis] < 0) {
      slab_lo[axis] = origin_[axis];
      slab_hi[axis] = old[axis];
    } else {
      continue;
    }
    resetBox(slab_lo, slab_hi);
    loadBox(slab_lo, slab_hi);
    // The next slabs only cover the overlap along this axis.
    lo[axis] = std::max(old[axis], origin_[axis]);
    hi[axis] = std::min(old[axis], origin_[axis]) + size_[axis];
  }
  return true;
}

namespace {

// Amanatides & Woo set-up in voxel units for the segment a -> b.
struct Walk {
  int cell[3], step[3];
  double t_max[3], t_delta[3];
  int steps;  // cells after the first one up to and including the last one
  Walk(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const Eigen::Vector3d d = b - a;
    steps = 0;
    for (int i = 0; i < 3; ++i) {
      cell[i] = static_cast<int>(std::floor(a[i]));
      const int last = static_cast<int>(std::floor(b[i]));
      steps += std::abs(last - cell[i]);
      if (d[i] > 0.0) {
        step[i] = 1;
        t_max[i] = (cell[i] + 1 - a[i]) / d[i];
        t_delta[i] = 1.0 / d[i];
      } else if (d[i] < 0.0) {
        step[i] = -1;
        t_max[i] = (cell[i] - a[i]) / d[i];
        t_delta[i] = -1.0 / d[i];
      } else {
        step[i] = 0;
        t_max[i] = std::numeric_limits<double>::infinity();
        t_delta[i] = std::numeric_limits<double>::infinity();
      }
    }
  }
  int next() {  // the axis stepped
    const int axis =
        t_max[0] < t_max[1] ? (t_max[0] < t_max[2] ? 0 : 2) : (t_max[1] < t_max[2] ? 1 : 2);
    cell[axis] += step[axis];
    t_max[axis] += t_delta[axis];
    return axis;
  }
};

}  // namespace

void OccupancyMap::keepOccupiedBesideHits(ScanStamps marks) {
  // A cell mapped occupied beside a surface this scan hit holds part of that surface: a ray
  // through it may have passed that part by a hair (rays graze a trunk's silhouette, and its
  // curved front crosses cells diagonally), so this scan does not clear it.
  uint8_t* const stamps = stamp_.data();
  for (const uint32_t hit : occupied_list_) {
    const Eigen::Vector3i g = cellOfSlot(hit);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const Eigen::Vector3i n = g + Eigen::Vector3i(dx, dy, dz);
          if (!inWindow(n)) continue;
          const int64_t slot = ringIndex(n);
          if (stamps[slot] != marks.hit && log_odds_[slot] > occ_threshold_)
            stamps[slot] = marks.kept;
        }
  }
}

void OccupancyMap::castFree(const Eigen::Vector3d& origin, const Eigen::Vector3d& end,
                            uint8_t free_stamp) {
  // The cells from the origin's up to (excluding) the end's, as OctoMap's computeRayKeys. Plain
  // scalars (no arrays indexed by the stepped axis) keep the walk in registers.
  const double inv = 1.0 / res_;
  const Walk w(origin * inv, end * inv);
  int cx = w.cell[0], cy = w.cell[1], cz = w.cell[2];
  int rx = positiveMod(cx, ring_.x()), ry = positiveMod(cy, ring_.y()),
      rz = positiveMod(cz, ring_.z());
  const int sx = w.step[0], sy = w.step[1], sz = w.step[2];
  double tx = w.t_max[0], ty = w.t_max[1], tz = w.t_max[2];
  const double dx = w.t_delta[0], dy = w.t_delta[1], dz = w.t_delta[2];
  const int nx = ring_.x(), ny = ring_.y(), nz = ring_.z();
  const int64_t bx = bricks_.x(), by = bricks_.y();
  // Cells of the window along each axis as unsigned offsets from its origin.
  const unsigned wx = static_cast<unsigned>(size_.x()), wy = static_cast<unsigned>(size_.y()),
                 wz = static_cast<unsigned>(size_.z());
  const int ox = origin_.x(), oy = origin_.y(), oz = origin_.z();
  uint8_t* const stamps = stamp_.data();
  // Appended without a branch (whether a cell is new to this scan is unpredictable).
  size_t count = free_list_.size();
  free_list_.resize(count + static_cast<size_t>(std::max(0, w.steps)));
  uint32_t* const list = free_list_.data();
  for (int k = 0; k < w.steps; ++k) {
    // The window is convex: a ray that left it does not come back.
    if (static_cast<unsigned>(cx - ox) >= wx || static_cast<unsigned>(cy - oy) >= wy ||
        static_cast<unsigned>(cz - oz) >= wz) {
      break;
    }
    const uint32_t slot =
        static_cast<uint32_t>(((((rz >> 3) * by) + (ry >> 3)) * bx + (rx >> 3)) << 9 |
                              ((rz & 7) << 6) | ((ry & 7) << 3) | (rx & 7));
    const uint8_t s = stamps[slot];
    // Stamps grow with the scans: a cell this scan freed, hit or keeps is at free_stamp or above.
    const bool fresh = s < free_stamp;
    stamps[slot] = fresh ? free_stamp : s;
    list[count] = slot;
    count += fresh;
    if (tx < ty && tx < tz) {
      cx += sx;
      rx += sx;
      rx = rx == nx ? 0 : (rx < 0 ? nx - 1 : rx);
      tx += dx;
    } else if (ty < tz) {
      cy += sy;
      ry += sy;
      ry = ry == ny ? 0 : (ry < 0 ? ny - 1 : ry);
      ty += dy;
    } else {
      cz += sz;
      rz += sz;
      rz = rz == nz ? 0 : (rz < 0 ? nz - 1 : rz);
      tz += dz;
    }
  }
  free_list_.resize(count);
}

Eigen::Vector3i OccupancyMap::cellOfSlot(uint32_t slot) const {
  const int lx = slot & 7, ly = (slot >> 3) & 7, lz = (slot >> 6) & 7;
  int64_t brick = slot >> 9;
  const int bx = static_cast<int>(brick % bricks_.x());
  brick /= bricks_.x();
  const int by = static_cast<int>(brick % bricks_.y());
  const int bz = static_cast<int>(brick / bricks_.y());
  const Eigen::Vector3i r(8 * bx + lx, 8 * by + ly, 8 * bz + lz);
  // The window cell congruent to r: origin + ((r - origin) mod ring).
  Eigen::Vector3i g;
  for (int i = 0; i < 3; ++i) g[i] = origin_[i] + positiveMod(r[i] - origin_[i], ring_[i]);
  return g;
}

void OccupancyMap::shiftStates(const Eigen::Vector3i& shift) {
  // In place: new cell l takes old cell l + shift. Rows are moved in the order that never
  // overwrites a row still to be read, then the cells that entered are cleared.
  const Eigen::Vector3i n = size_;
  if ((shift.cwiseAbs().array() >= n.array()).any()) {
    std::fill(states_.begin(), states_.end(), 0);
    return;
  }
  const Eigen::Vector3i lo = (-shift).cwiseMax(0), hi = (n - shift).cwiseMin(n);
  const int64_t offset = shift.x() + int64_t{n.x()} * (shift.y() + int64_t{n.y()} * shift.z());
  auto index = [&](int x, int y, int z) { return x + int64_t{n.x()} * (y + int64_t{n.y()} * z); };
  const size_t row = static_cast<size_t>(hi.x() - lo.x());
  auto moveRow = [&](int y, int z) {
    const int64_t dst = index(lo.x(), y, z);
    std::memmove(&states_[dst], &states_[dst + offset], row);
  };
  if (offset > 0) {
    for (int z = lo.z(); z < hi.z(); ++z)
      for (int y = lo.y(); y < hi.y(); ++y) moveRow(y, z);
  } else if (offset < 0) {
    for (int z = hi.z() - 1; z >= lo.z(); --z)
      for (int y = hi.y() - 1; y >= lo.y(); --y) moveRow(y, z);
  }
  for (int z = 0; z < n.z(); ++z) {
    for (int y = 0; y < n.y(); ++y) {
      uint8_t* r = &states_[index(0, y, z)];
      if (z < lo.z() || z >= hi.z() || y < lo.y() || y >= hi.y()) {
        std::memset(r, 0, n.x());
      } else {
        std::memset(r, 0, lo.x());
        std::memset(r + hi.x(), 0, n.x() - hi.x());
      }
    }
  }
}

Occupancy OccupancyMap::stateAt(const Eigen::Vector3d& p) const {
  const Eigen::Vector3i g((p / res_).array().floor().cast<int>());
  if (!has_window_ || !inWindow(g)) return Occupancy::kUnknown;
  return static_cast<Occupancy>(states_[windowIndex(g)]);
}

VoxelGrid OccupancyMap::window() const {
  VoxelGrid grid(res_, origin_, size_);
  for (size_t i = 0; i < states_.size(); ++i) {
    if (states_[i] != 0)
      grid.setLinear(static_cast<int64_t>(i), static_cast<Occupancy>(states_[i]));
  }
  return grid;
}

void OccupancyMap::apply(uint32_t slot, float delta, InsertStats* stats) {
  float& value = log_odds_[slot];
  const bool known = !std::isnan(value);
  const float old = known ? value : 0.0f;
  const float updated = std::clamp(old + delta, clamp_min_, clamp_max_);
  if (known && updated == old) return;  // clamped already: nothing changes
  ++stats->cells_updated;
  value = updated;
  // The tree leaf is written back later (flush()), once for all updates until then.
  if (!dirty_[slot]) {
    dirty_[slot] = 1;
    dirty_list_.push_back(slot);
  }
  const Occupancy state = stateOf(updated);
  if (!known || stateOf(old) != state) {
    const Eigen::Vector3i g = cellOfSlot(slot);
    states_[windowIndex(g)] = static_cast<uint8_t>(state);
    markChanged(g);
  }
}

size_t OccupancyMap::flush() {
  size_t created = 0;
  for (uint32_t slot : dirty_list_) {
    dirty_[slot] = 0;
    octomap::OcTreeNode*& node = node_[slot];
    if (node) {
      node->setLogOdds(log_odds_[slot]);
    } else {
      node = tree_->setNodeValue(toKey(cellOfSlot(slot)), log_odds_[slot], /*lazy_eval=*/true);
      ++created;
    }
  }
  dirty_list_.clear();
  return created;
}

InsertStats OccupancyMap::insert(const FilteredScan& scan) {
  InsertStats stats;
  if (!has_window_) return stats;
  // Three stamps per scan, above those of every earlier scan; on wrap-around (every 84 scans)
  // every stamp is cleared.
  if (generation_ >= 84) {
    std::fill(stamp_.begin(), stamp_.end(), 0);
    generation_ = 0;
  }
  ++generation_;
  const ScanStamps marks{static_cast<uint8_t>(3 * generation_),
                         static_cast<uint8_t>(3 * generation_ + 1),
                         static_cast<uint8_t>(3 * generation_ + 2)};
  occupied_list_.clear();
  free_list_.clear();
  const double inv = 1.0 / res_;
  for (const Eigen::Vector3f& p : scan.returns) {
    const Eigen::Vector3i g((p.cast<double>() * inv).array().floor().cast<int>());
    if (!inWindow(g)) {
      ++stats.ends_outside;
      continue;
    }
    const int64_t idx = ringIndex(g);
    if (stamp_[idx] == marks.hit) continue;
    stamp_[idx] = marks.hit;
    occupied_list_.push_back(static_cast<uint32_t>(idx));
  }
  keepOccupiedBesideHits(marks);
  for (const auto* ends : {&scan.returns, &scan.free_ends}) {
    for (const Eigen::Vector3f& p : *ends) castFree(scan.origin, p.cast<double>(), marks.free);
  }
  stats.rays = scan.returns.size() + scan.free_ends.size();
  stats.cells_occupied = occupied_list_.size();
  stats.cells_free = free_list_.size();
  for (uint32_t slot : occupied_list_) apply(slot, log_hit_, &stats);
  for (uint32_t slot : free_list_) apply(slot, log_miss_, &stats);
  return stats;
}

std::vector<CellChange> OccupancyMap::takeChanges() {
  return windowChangesOf(takeChangedCells());
}

std::vector<int64_t> OccupancyMap::takeChangedCells() {
  return std::exchange(changed_, {});
}

std::vector<CellChange> OccupancyMap::windowChangesOf(const std::vector<int64_t>& cells) const {
  std::vector<int64_t> linear;
  linear.reserve(cells.size());
  for (int64_t packed : cells) {
    const Eigen::Vector3i g = unpack(packed);
    if (inWindow(g)) linear.push_back(windowIndex(g));
  }
  std::sort(linear.begin(), linear.end());
  linear.erase(std::unique(linear.begin(), linear.end()), linear.end());
  std::vector<CellChange> out;
  out.reserve(linear.size());
  for (int64_t i : linear) out.emplace_back(i, static_cast<Occupancy>(states_[i]));
  return out;
}

Occupancy OccupancyMap::query(const Eigen::Vector3d& p) const {
  const Eigen::Vector3i g((p / res_).array().floor().cast<int>());
  if (has_window_ && inWindow(g)) {
    // The window holds the newest values (the tree may wait for flush()).
    const float value = log_odds_[ringIndex(g)];
    return std::isnan(value) ? Occupancy::kUnknown : stateOf(value);
  }
  if ((g.array().abs() >= kKeyOffset).any()) return Occupancy::kUnknown;
  const octomap::OcTreeNode* node = tree_->search(toKey(g));
  if (!node) return Occupancy::kUnknown;
  return stateOf(node->getLogOdds());
}

void OccupancyMap::pruneOutsideWindow() {
  if (!has_window_ || !moved_since_prune_) return;
  // Only the region the window covered since the last pruning can hold new prunable nodes.
  const Eigen::Vector3i last = origin_ + size_ - Eigen::Vector3i::Ones();
  tree_->pruneOutside(origin_, last, region_lo_, region_hi_);
  region_lo_ = origin_;
  region_hi_ = last;
  moved_since_prune_ = false;
}

}  // namespace mmh::mapping
