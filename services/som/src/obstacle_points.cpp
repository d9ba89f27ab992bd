#include "mmh/som/obstacle_points.hpp"

#include "mmh/common/collision_check.hpp"

#include <algorithm>
#include <cmath>

namespace mmh::som {

bool cellRange(const VoxelGrid& grid, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
               Eigen::Vector3i* first, Eigen::Vector3i* last) {
  const double res = grid.resolution();
  for (int i = 0; i < 3; ++i) {
    const double f = std::ceil(lo[i] / res - 0.5) - grid.originIndex()[i];
    const double l = std::floor(hi[i] / res - 0.5) - grid.originIndex()[i];
    (*first)[i] = static_cast<int>(std::clamp(f, 0.0, double(grid.size()[i])));
    (*last)[i] = static_cast<int>(std::clamp(l, -1.0, double(grid.size()[i] - 1)));
    if ((*first)[i] > (*last)[i]) return false;
  }
  return true;
}

namespace {
constexpr double kFaceInset = 1e-6;  // m
}  // namespace

bool withinInflation(const VoxelGrid& grid, const Eigen::Vector3i& local,
                     const std::vector<Eigen::Vector3i>& offsets) {
  for (const Eigen::Vector3i& o : offsets)
    if (grid.at(local + o) == Occupancy::kOccupied) return true;
  return false;
}

bool EscapeZone::frees(const VoxelGrid& grid, const Eigen::Vector3i& local,
                       const Eigen::Vector3d& c) const {
  if (radius <= 0.0 || grid.at(local) == Occupancy::kOccupied) return false;
  if ((c - center).squaredNorm() > radius * radius) return false;
  // The start's own cell is free (its centre may lie nearer than the start itself), as in
  // GridAStar: else its centre is an obstacle point on every seed from the start.
  if (local == grid.localIndexOf(center)) return true;
  const auto [entry, added] = keeps_distance_.try_emplace(grid.linearIndex(local), false);
  if (added) entry->second = keepsEscapeDistance(grid, c, min_distance, 0.0);
  return entry->second;
}

bool BlockedMask::build(const VoxelGrid& grid, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                        const EscapeZone& escape, double check_inflation_m,
                        double check_face_clearance_m, bool check_whole_cells) {
  escape_faces_.clear();
  check_faces_.clear();
  Eigen::Vector3i f, l;
  if (!cellRange(grid, lo, hi, &f, &l)) {
    n_.setZero();
    mask_.clear();
    return false;
  }
  res_ = grid.resolution();
  n_ = l - f + Eigen::Vector3i::Ones();
  corner_ = ((grid.originIndex() + f).cast<double>().array() + 0.5) * res_;
  sy_ = n_.x() + 2;
  sz_ = sy_ * (n_.y() + 2);
  mask_.assign(static_cast<size_t>(sz_) * (n_.z() + 2), 0);
  const Eigen::Vector3i& size = grid.size();
  // Rows of the window clipped to the bordered box; everything else stays 0 (not blocked).
  const int x0 = std::max(0, f.x() - 1), x1 = std::min(size.x() - 1, l.x() + 1);
  for (int z = std::max(0, f.z() - 1); z <= std::min(size.z() - 1, l.z() + 1); ++z) {
    for (int y = std::max(0, f.y() - 1); y <= std::min(size.y() - 1, l.y() + 1); ++y) {
      const uint16_t* counts = grid.blockedCounts() + grid.linearIndex(Eigen::Vector3i(x0, y, z));
      uint8_t* m = &mask_[(z - f.z() + 1) * sz_ + (y - f.y() + 1) * sy_ + (x0 - f.x() + 1)];
      const int n = x1 - x0 + 1;
      for (int x = 0; x < n; ++x) m[x] = counts[x] != 0;  // vectorised
    }
  }
  if (escape.radius > 0.0) {
    // Inflated (not occupied) cells around the start are free. Only the mask cells round the
    // escape zone can be (a cell to spare on each side; the distance test below decides).
    const double r2 = escape.radius * escape.radius;
    Eigen::Vector3i near_lo, near_hi;  // mask indices, border included
    for (int i = 0; i < 3; ++i) {
      const double from = (escape.center[i] - escape.radius - corner_[i]) / res_;
      const double to = (escape.center[i] + escape.radius - corner_[i]) / res_;
      near_lo[i] = static_cast<int>(std::clamp(std::floor(from), 0.0, double(n_[i] + 1)));
      near_hi[i] = static_cast<int>(std::clamp(std::ceil(to) + 2.0, 0.0, double(n_[i] + 1)));
    }
    for (int z = near_lo.z(); z <= near_hi.z(); ++z)
      for (int y = near_lo.y(); y <= near_hi.y(); ++y)
        for (int x = near_lo.x(); x <= near_hi.x(); ++x) {
          uint8_t& m = mask_[z * sz_ + y * sy_ + x];
          if (!m) continue;
          const Eigen::Vector3d c = centerOf(x - 1, y - 1, z - 1);
          if ((c - escape.center).squaredNorm() > r2) continue;
          const Eigen::Vector3i local = f + Eigen::Vector3i(x - 1, y - 1, z - 1);
          if (escape.frees(grid, local, c)) m = 2;
        }
    // The faces through the obstacle points may pass through the centres of the blocked cells
    // next to the freed ones, so a trajectory inside the polytopes could still run half a voxel
    // into them: nearer to the obstacle than the escape rule allows, into cells that a check
    // with a smaller margin (the arbiter's 0.25 m) blocks, though the freed cells it keeps to are
    // clear of it. The centre of each face between a freed cell and a blocked neighbour is an
    // obstacle point as well, which keeps the polytopes to the freed cells' side of those faces.
    const Eigen::Vector3i start_cell =
        grid.localIndexOf(escape.center) - f + Eigen::Vector3i::Ones();
    const int64_t step[3] = {1, sy_, sz_};
    for (int z = std::max(1, near_lo.z()); z <= std::min(n_.z(), near_hi.z()); ++z)
      for (int y = std::max(1, near_lo.y()); y <= std::min(n_.y(), near_hi.y()); ++y)
        for (int x = std::max(1, near_lo.x()); x <= std::min(n_.x(), near_hi.x()); ++x) {
          const int64_t i = z * sz_ + y * sy_ + x;
          if (mask_[i] != 2 || Eigen::Vector3i(x, y, z) == start_cell) continue;
          const Eigen::Vector3d c = centerOf(x - 1, y - 1, z - 1);
          for (int axis = 0; axis < 3; ++axis)
            for (int sign : {-1, 1}) {
              if (mask_[i + sign * step[axis]] != 1) continue;
              Eigen::Vector3d n = c;
              n[axis] += sign * res_;
              // Only the cells the escape zone keeps blocked (outside it, blocked cells are
              // obstacle points as anywhere); the point lies a hair inside the blocked cell.
              if ((n - escape.center).squaredNorm() > r2) continue;
              Eigen::Vector3d q = c;
              q[axis] += sign * (0.5 * res_ + kFaceInset);
              escape_faces_.push_back(q);
            }
        }
    for (int z = near_lo.z(); z <= near_hi.z(); ++z)
      for (int y = near_lo.y(); y <= near_hi.y(); ++y)
        for (int x = near_lo.x(); x <= near_hi.x(); ++x) {
          uint8_t& m = mask_[z * sz_ + y * sy_ + x];
          if (m == 2) m = 0;
        }
  }
  if (check_inflation_m > 0.0 && check_whole_cells)
    addCheckCellFences(grid, f, check_inflation_m, check_face_clearance_m);
  else if (check_inflation_m > 0.0)
    addCheckFaces(grid, f, check_inflation_m, check_face_clearance_m);
  return true;
}

void BlockedMask::addCheckFaces(const VoxelGrid& grid, const Eigen::Vector3i& first,
                                double check_inflation_m, double clearance_m) {
  // A polytope face through a surface cell's centre leaves the cell's outer half inside the
  // polytope; where the arbiter's smaller margin still blocks that cell, points just off its
  // faces towards the unblocked neighbours keep the polytopes out of it. Just off: a verified
  // trajectory may leave its polytopes by the verification's tolerance, and a point on the face
  // itself let answers graze the cell, which the arbiter then refused round after round.
  const std::vector<Eigen::Vector3i> offsets =
      VoxelGrid::offsetsWithin(check_inflation_m, grid.resolution());
  const int64_t step[3] = {1, sy_, sz_};
  for (int z = 1; z < n_.z() + 1; ++z)
    for (int y = 1; y < n_.y() + 1; ++y)
      for (int x = 1; x < n_.x() + 1; ++x) {
        const int64_t i = z * sz_ + y * sy_ + x;
        if (mask_[i] != 1) continue;
        bool surface = false;
        for (int axis = 0; axis < 3 && !surface; ++axis)
          surface = mask_[i - step[axis]] == 0 || mask_[i + step[axis]] == 0;
        if (!surface) continue;
        const Eigen::Vector3i local = first + Eigen::Vector3i(x - 1, y - 1, z - 1);
        if (!withinInflation(grid, local, offsets)) continue;
        const Eigen::Vector3d c = centerOf(x - 1, y - 1, z - 1);
        for (int axis = 0; axis < 3; ++axis)
          for (int sign : {-1, 1}) {
            if (mask_[i + sign * step[axis]] != 0) continue;
            Eigen::Vector3d q = c;
            q[axis] += sign * (0.5 * res_ + clearance_m - kFaceInset);
            check_faces_.push_back(q);
          }
      }
}

void BlockedMask::addCheckCellFences(const VoxelGrid& grid, const Eigen::Vector3i& first,
                                     double check_inflation_m, double clearance_m) {
  // The face points of addCheckFaces keep the polytopes off a face's centre only: a polytope may
  // still cut across a corner of the cell, through the outer half of a neighbour that only the
  // planning margin blocks or past an edge it shares with an unblocked cell.
  static const std::vector<Eigen::Vector3i> kDirections = [] {
    std::vector<Eigen::Vector3i> d;
    for (int z = -1; z <= 1; ++z)
      for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x)
          if (x != 0 || y != 0 || z != 0) d.emplace_back(x, y, z);
    return d;
  }();
  const std::vector<Eigen::Vector3i> offsets =
      VoxelGrid::offsetsWithin(check_inflation_m, grid.resolution());
  within_check_.assign(mask_.size(), 0);  // only blocked cells can be within the smaller margin
  for (int z = 0; z < n_.z() + 2; ++z)
    for (int y = 0; y < n_.y() + 2; ++y)
      for (int x = 0; x < n_.x() + 2; ++x) {
        const int64_t i = z * sz_ + y * sy_ + x;
        if (mask_[i] == 1)
          within_check_[i] =
              withinInflation(grid, first + Eigen::Vector3i(x - 1, y - 1, z - 1), offsets);
      }
  const double half = 0.5 * res_;
  const double reach = half + clearance_m - kFaceInset;
  for (int z = 1; z < n_.z() + 1; ++z)
    for (int y = 1; y < n_.y() + 1; ++y)
      for (int x = 1; x < n_.x() + 1; ++x) {
        const int64_t i = z * sz_ + y * sy_ + x;
        if (!within_check_[i]) continue;
        const Eigen::Vector3d c = centerOf(x - 1, y - 1, z - 1);
        for (const Eigen::Vector3i& d : kDirections) {
          if (within_check_[i + d.x() + d.y() * sy_ + d.z() * sz_]) continue;
          if (d.cwiseAbs().sum() > 1) {  // an edge or a corner
            check_faces_.push_back(c + reach * d.cast<double>());
            continue;
          }
          const int axis = d.x() != 0 ? 0 : (d.y() != 0 ? 1 : 2);
          const int u = (axis + 1) % 3, v = (axis + 2) % 3;
          for (int a = -1; a <= 1; ++a)
            for (int b = -1; b <= 1; ++b) {
              Eigen::Vector3d q = c;
              q[axis] += d[axis] * reach;
              q[u] += a * half;
              q[v] += b * half;
              check_faces_.push_back(q);
            }
        }
      }
}

void BlockedMask::surfacePoints(std::vector<Eigen::Vector3d>* out) const {
  out->clear();
  const int nx = n_.x(), ny = n_.y(), nz = n_.z();
  const int64_t sy = sy_, sz = sz_;
  row_.resize(nx + 2);
  uint8_t* __restrict surface = row_.data();
  for (int z = 1; z <= nz; ++z) {
    for (int y = 1; y <= ny; ++y) {
      const uint8_t* __restrict c = &mask_[z * sz + y * sy];
      // Blocked with a free 6-neighbour, as bytes over the whole row (vectorised) ...
      uint8_t any = 0;
      for (int x = 1; x <= nx; ++x) {
        const uint8_t s =
            c[x] & ~(c[x - 1] & c[x + 1] & c[x - sy] & c[x + sy] & c[x - sz] & c[x + sz]);
        surface[x] = s;
        any |= s;
      }
      if (!any) continue;
      // ... then the few set cells become points.
      for (int x = 1; x <= nx; ++x)
        if (surface[x] & 1) out->push_back(centerOf(x - 1, y - 1, z - 1));
    }
  }
  out->insert(out->end(), escape_faces_.begin(), escape_faces_.end());
  out->insert(out->end(), check_faces_.begin(), check_faces_.end());
}

void BlockedMask::pointsInside(const Polytope& poly, std::vector<Eigen::Vector3d>* out) const {
  out->clear();
  const Polytope::Matrix& h = poly.halfspaces();
  const int faces = static_cast<int>(h.rows());
  // Along a row (y, z fixed) face i allows a_x t <= slack_i(y, z), with t the offset from the
  // box corner in x; slack is affine in (y, z), so it is updated without divisions.
  // slack = base + dy * y + dz * z; inv = 1 / a_x (0 if a_x = 0); sign of a_x.
  faces_.resize(faces);
  for (int i = 0; i < faces; ++i) {
    FaceRow& f = faces_[i];
    f.base = h(i, 3) - h.row(i).head<3>().dot(corner_);
    f.dy = -h(i, 1) * res_;
    f.dz = -h(i, 2) * res_;
    const double a = h(i, 0);
    f.sign = a > 1e-12 ? 1 : (a < -1e-12 ? -1 : 0);
    f.inv = f.sign != 0 ? 1.0 / a : 0.0;
  }
  for (int z = 0; z < n_.z(); ++z) {
    for (int y = 0; y < n_.y(); ++y) {
      double t0 = -0.5 * res_, t1 = (n_.x() - 0.5) * res_;
      for (int i = 0; i < faces && t0 <= t1; ++i) {
        const FaceRow& f = faces_[i];
        const double slack = f.base + f.dy * y + f.dz * z;
        if (f.sign > 0) {
          t1 = std::min(t1, slack * f.inv);
        } else if (f.sign < 0) {
          t0 = std::max(t0, slack * f.inv);
        } else if (slack <= 0.0) {
          t1 = t0 - 1.0;
        }
      }
      if (t0 > t1) continue;
      const int x0 = std::max(0, static_cast<int>(std::floor(t0 / res_)));
      const int x1 = std::min(n_.x() - 1, static_cast<int>(std::ceil(t1 / res_)));
      const uint8_t* m = &mask_[(z + 1) * sz_ + (y + 1) * sy_ + 1];
      for (int x = x0; x <= x1; ++x) {
        if (!m[x]) continue;
        const Eigen::Vector3d c = centerOf(x, y, z);
        if (poly.maxViolation(c) < 0.0) out->push_back(c);
      }
    }
  }
}

void blockedSurfacePoints(const VoxelGrid& grid, const Eigen::Vector3d& lo,
                          const Eigen::Vector3d& hi, const EscapeZone& escape,
                          std::vector<Eigen::Vector3d>* out) {
  BlockedMask mask;
  out->clear();
  if (mask.build(grid, lo, hi, escape)) mask.surfacePoints(out);
}

void blockedPointsInside(const VoxelGrid& grid, const Eigen::Vector3d& lo,
                         const Eigen::Vector3d& hi, const Polytope& poly, const EscapeZone& escape,
                         std::vector<Eigen::Vector3d>* out) {
  BlockedMask mask;
  out->clear();
  if (mask.build(grid, lo, hi, escape)) mask.pointsInside(poly, out);
}

}  // namespace mmh::som
