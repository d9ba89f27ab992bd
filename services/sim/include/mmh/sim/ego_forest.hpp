// The random forest of EGO-Planner's and Fast-Planner's simulators, as a second world family:
// round pillars built of 0.1 m x 0.1 m columns, each column with its own height (ragged tops),
// plus thin vertical elliptic rings. Our own generator after the published description; the
// density counts pillars per square metre of the box footprint, and one ring is added per 15
// pillars (Fast-Planner's default: 150 pillars and 10 rings in 40 x 20 m, 0.19 obs/m^2).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "mmh/sim/elliptic_ring.hpp"

namespace mmh::sim {

// Edge of the columns; they sit on the global grid [i e, (i + 1) e) x [j e, (j + 1) e).
constexpr double kEgoColumnEdgeM = 0.1;

struct EgoForestSpec {
  Eigen::Vector3d size_m = Eigen::Vector3d(50.0, 50.0, 3.0);  // box centred on x = y = 0
  double density_per_m2 = 0.1;                                // pillars per m^2 of the footprint
  uint64_t seed = 7;
  Eigen::Vector3d start = Eigen::Vector3d(-19.95, 0.0, 1.2);
  Eigen::Vector3d goal = Eigen::Vector3d(19.95, 0.0, 1.2);
  double clearance_m = 2.0;           // no obstacle closer than this to start or goal (in xy)
  double min_center_spacing_m = 0.8;  // between any two obstacle centres (pillars and rings)
  int pillars_per_ring = 15;
};

struct EgoColumn {
  int ix = 0, iy = 0;   // grid cell of the column
  double height_m = 0;  // the column spans z in [0, height_m]
};

struct EgoPillar {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  // a column centre
  double diameter_m = 0.5;
  std::vector<EgoColumn> columns;  // the cells whose centres lie within diameter / 2
};

struct EgoForest {
  std::vector<EgoPillar> pillars;
  std::vector<EllipticRing> rings;
};

// round(density x footprint) pillars and pillars / pillars_per_ring rings, reproducible from the
// seed. Pillar diameter U(0.5, 0.7) x U(0.5, 1.5) m, column heights U(0, size z); rings: semi-axes
// U(0.5, 0.7) m (horizontal) x U(0.7, 1.2) m (vertical), centre height U(1.2, 1.3) m, yaw
// U(-0.5, 0.5) rad from facing the x axis, 0.1 m thick. Throws std::invalid_argument when the
// spec is impossible (negative density, no room for the obstacles).
EgoForest generateEgoForest(const EgoForestSpec& spec);

}  // namespace mmh::sim
