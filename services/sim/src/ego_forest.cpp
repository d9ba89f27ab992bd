#include "mmh/sim/ego_forest.hpp"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace mmh::sim {
namespace {

// Farthest a column's square reaches beyond its centre.
constexpr double kColumnHalfDiagonal = 0.5 * kEgoColumnEdgeM * M_SQRT2;

int cellOf(double x) {
  return static_cast<int>(std::floor(x / kEgoColumnEdgeM));
}

double cellCenter(int i) {
  return (i + 0.5) * kEgoColumnEdgeM;
}

}  // namespace

EgoForest generateEgoForest(const EgoForestSpec& spec) {
  if (!(spec.density_per_m2 >= 0.0) || !(spec.size_m.x() > 0.0) || !(spec.size_m.y() > 0.0) ||
      !(spec.size_m.z() > 0.0) || spec.pillars_per_ring < 1) {
    throw std::invalid_argument(
        "ego-forest: density must be >= 0, the box size positive, pillars_per_ring >= 1");
  }
  const double area = spec.size_m.x() * spec.size_m.y();
  const int pillar_count = static_cast<int>(std::lround(spec.density_per_m2 * area));
  const int ring_count = pillar_count / spec.pillars_per_ring;
  std::mt19937_64 rng(spec.seed);
  std::uniform_real_distribution<double> ux(-0.5 * spec.size_m.x(), 0.5 * spec.size_m.x());
  std::uniform_real_distribution<double> uy(-0.5 * spec.size_m.y(), 0.5 * spec.size_m.y());
  std::uniform_real_distribution<double> u_width(0.5, 0.7), u_scale(0.5, 1.5);
  std::uniform_real_distribution<double> u_height(0.0, spec.size_m.z());
  std::uniform_real_distribution<double> u_semi_h(0.5, 0.7), u_semi_v(0.7, 1.2);
  std::uniform_real_distribution<double> u_ring_z(1.2, 1.3), u_yaw(-0.5, 0.5);

  std::vector<Eigen::Vector2d> centers;
  const int total = pillar_count + ring_count;
  const int max_attempts = 1000 * std::max(1, total);
  int attempts = 0;
  // A centre that keeps `reach` (the obstacle's extent around it) clear of start and goal and
  // min_center_spacing_m from every other centre.
  auto place = [&](double reach) {
    for (;;) {
      if (++attempts > max_attempts) {
        throw std::invalid_argument("ego-forest: cannot place " + std::to_string(total) +
                                    " obstacles with the requested spacing and clearance");
      }
      // Centres snap to a column centre, so that a pillar's footprint is symmetric about it.
      const Eigen::Vector2d c(cellCenter(cellOf(ux(rng))), cellCenter(cellOf(uy(rng))));
      if ((c - spec.start.head<2>()).norm() - reach < spec.clearance_m) continue;
      if ((c - spec.goal.head<2>()).norm() - reach < spec.clearance_m) continue;
      bool spaced = true;
      for (const Eigen::Vector2d& o : centers) {
        if ((o - c).norm() < spec.min_center_spacing_m) {
          spaced = false;
          break;
        }
      }
      if (!spaced) continue;
      centers.push_back(c);
      return c;
    }
  };

  EgoForest forest;
  forest.pillars.reserve(pillar_count);
  for (int k = 0; k < pillar_count; ++k) {
    EgoPillar pillar;
    pillar.diameter_m = u_width(rng) * u_scale(rng);
    const double radius = 0.5 * pillar.diameter_m;
    pillar.center = place(radius + kColumnHalfDiagonal);
    const int cx = cellOf(pillar.center.x()), cy = cellOf(pillar.center.y());
    const int reach = static_cast<int>(std::floor(radius / kEgoColumnEdgeM));
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dx = -reach; dx <= reach; ++dx) {
        if (std::hypot(dx, dy) * kEgoColumnEdgeM > radius) continue;
        pillar.columns.push_back(EgoColumn{cx + dx, cy + dy, u_height(rng)});
      }
    }
    forest.pillars.push_back(std::move(pillar));
  }
  forest.rings.reserve(ring_count);
  for (int k = 0; k < ring_count; ++k) {
    EllipticRing ring;
    ring.semi_horizontal_m = u_semi_h(rng);
    ring.semi_vertical_m = u_semi_v(rng);
    ring.yaw = u_yaw(rng);
    ring.tube_radius_m = 0.05;
    const double z = u_ring_z(rng);
    const Eigen::Vector2d c = place(ring.semi_horizontal_m + ring.tube_radius_m);
    ring.center = Eigen::Vector3d(c.x(), c.y(), z);
    forest.rings.push_back(ring);
  }
  return forest;
}

}  // namespace mmh::sim
