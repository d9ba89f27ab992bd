// Scenarios of the EAM benchmark: SOM's forest scenarios with a new pillar inserted across the
// current trajectory (straight, or EAM's own collision-free answer before the pillar appeared).
// Header-only so that the benchmark and ad-hoc tools can share it.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "mmh/common/config.hpp"
#include "mmh/common/grid_astar.hpp"
#include "mmh/common/node_options.hpp"
#include "mmh/eam/planner.hpp"
#include "scenarios.hpp"

namespace mmh::eam_bench {

struct EamScenario {
  int map = 0;  // index into EamSet::grids
  Eigen::Vector3d start, target;
  mmh::Trajectory reference;
  std::vector<int64_t> pillar;  // cells made occupied (free before)
  bool path_exists = false;     // A* start -> target with the pillar
};

struct EamSet {
  std::vector<std::shared_ptr<mmh::VoxelGrid>> grids;  // one working copy per forest
  std::vector<EamScenario> scenarios;
};

inline mmh::eam::EamParams benchParams() {
  return mmh::eam::loadEamParams(mmh::Config::loadFile(mmh::defaultConfigPath()));
}

// Straight line, speed rising smoothly (cubic in time) to v_max, cruising, and falling to rest.
inline mmh::Trajectory straightReference(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                         double vmax, double amax) {
  const Eigen::Vector3d d = (b - a).normalized();
  const double len = (b - a).norm();
  double v = vmax, ta = 1.5 * v / amax;  // peak acceleration of the cubic speed ramp = 1.5 v / ta
  if (v * ta > len) {                    // too short to reach v_max
    ta = std::sqrt(1.5 * len / amax);
    v = len / ta;
  }
  const double ramp = 0.5 * v * ta, cruise = len - 2.0 * ramp;
  std::vector<mmh::Piece> pieces;
  mmh::Piece up;
  up.duration = ta;
  up.coeffs.col(0) = a;
  up.coeffs.col(3) = d * v / (ta * ta);
  up.coeffs.col(4) = -d * v / (2.0 * ta * ta * ta);
  pieces.push_back(up);
  if (cruise > 1e-9) {
    mmh::Piece c;
    c.duration = cruise / v;
    c.coeffs.col(0) = a + d * ramp;
    c.coeffs.col(1) = d * v;
    pieces.push_back(c);
  }
  mmh::Piece down;
  down.duration = ta;
  down.coeffs.col(0) = a + d * (ramp + std::max(0.0, cruise));
  down.coeffs.col(1) = d * v;
  down.coeffs.col(3) = -d * v / (ta * ta);
  down.coeffs.col(4) = d * v / (2.0 * ta * ta * ta);
  pieces.push_back(down);
  return mmh::Trajectory(pieces);
}

// Polyline flown at constant speed (linear pieces): a rough guess for EAM to smooth.
inline mmh::Trajectory polylineReference(const std::vector<Eigen::Vector3d>& path, double speed) {
  std::vector<mmh::Piece> pieces;
  for (size_t k = 0; k + 1 < path.size(); ++k) {
    const double len = (path[k + 1] - path[k]).norm();
    if (len < 1e-6) continue;
    mmh::Piece p;
    p.duration = len / speed;
    p.coeffs.col(0) = path[k];
    p.coeffs.col(1) = (path[k + 1] - path[k]) / p.duration;
    pieces.push_back(p);
  }
  return mmh::Trajectory(pieces);
}

inline std::vector<int64_t> pillarCells(const mmh::VoxelGrid& g, const Eigen::Vector2d& c,
                                        double r) {
  std::vector<int64_t> cells;
  const double res = g.resolution();
  const Eigen::Vector3i lo = g.localIndexOf(Eigen::Vector3d(c.x() - r, c.y() - r, 0.0));
  const Eigen::Vector3i hi = g.localIndexOf(Eigen::Vector3d(c.x() + r, c.y() + r, 0.0));
  for (int z = 0; z < g.size().z(); ++z) {
    for (int y = std::max(0, lo.y()); y <= std::min(g.size().y() - 1, hi.y()); ++y) {
      for (int x = std::max(0, lo.x()); x <= std::min(g.size().x() - 1, hi.x()); ++x) {
        const Eigen::Vector3i cell(x, y, z);
        const Eigen::Vector3d p = g.centerOfLocal(cell);
        if ((p.head<2>() - c).norm() > r) continue;
        const int64_t i = g.linearIndex(cell);
        if (g.atLinear(i) != mmh::Occupancy::kOccupied) cells.push_back(i);
      }
    }
  }
  (void)res;
  return cells;
}

inline void setPillar(mmh::VoxelGrid& g, const std::vector<int64_t>& cells, bool on) {
  for (int64_t i : cells) g.setLinear(i, on ? mmh::Occupancy::kOccupied : mmh::Occupancy::kFree);
}

inline mmh::AStarOptions bandOptions() {
  mmh::AStarOptions o;
  o.min_bound = Eigen::Vector3d(-1e9, -1e9, 0.3);
  o.max_bound = Eigen::Vector3d(1e9, 1e9, 2.7);
  return o;
}

// Builds the 50 scenarios of one density; `committed` selects the reference kind.
inline EamSet makeSet(double density, bool committed) {
  const mmh::eam::EamParams params = benchParams();
  mmh::ScenarioSpec spec;
  spec.density_per_m2 = density;
  spec.maps = 10;
  spec.per_map = 5;
  const std::vector<mmh::PlanningScenario> base = mmh::makeForestScenarios(spec);
  EamSet set;
  std::map<const mmh::VoxelGrid*, int> map_index;
  mmh::GridAStar astar;
  mmh::eam::Planner planner(params);
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> along(0.3, 0.7), radius(0.25, 0.5), side(-0.2, 0.2);
  for (const mmh::PlanningScenario& s : base) {
    auto it = map_index.find(s.grid.get());
    if (it == map_index.end()) {
      it = map_index.emplace(s.grid.get(), static_cast<int>(set.grids.size())).first;
      set.grids.push_back(std::make_shared<mmh::VoxelGrid>(*s.grid));
    }
    mmh::VoxelGrid& grid = *set.grids[it->second];
    EamScenario e;
    e.map = it->second;
    e.start = s.start;
    e.target = s.target;
    e.reference = straightReference(s.start, s.target, params.max_vel_mps, params.max_acc_mps2);
    if (committed) {
      // The committed trajectory: EAM's answer on the forest before the pillar, from the
      // straight guess or, when that fails, from the A* path flown at 70% of v_max.
      mmh::eam::PlanRequest req;
      req.start.position = s.start;
      req.target = s.target;
      req.reference = e.reference;
      mmh::eam::PlanResult r = planner.plan(grid, req);
      if (!r.ok) {
        const mmh::AStarResult path = astar.search(grid, s.start, s.target, bandOptions());
        if (path.ok()) {
          req.reference =
              polylineReference(mmh::shortenPath(grid, path.path), 0.7 * params.max_vel_mps);
          r = planner.plan(grid, req);
        }
      }
      if (!r.ok) {
        e.path_exists = false;  // no committed trajectory to threaten: not a scenario
        set.scenarios.push_back(std::move(e));
        continue;
      }
      e.reference = r.trajectory;
    }
    // A pillar across the reference, between 30% and 70% of its duration, that leaves a path.
    for (int attempt = 0; attempt < 30; ++attempt) {
      const double t = along(rng) * e.reference.duration();
      const Eigen::Vector3d on = e.reference.position(t);
      const Eigen::Vector3d dir = e.reference.velocity(t).normalized();
      const Eigen::Vector3d lateral(-dir.y(), dir.x(), 0.0);
      const Eigen::Vector3d c = on + side(rng) * lateral;
      std::vector<int64_t> cells = pillarCells(grid, c.head<2>(), radius(rng));
      setPillar(grid, cells, true);
      const bool ends_free = !grid.isBlockedPoint(e.start) && !grid.isBlockedPoint(e.target);
      const bool path = ends_free && astar.search(grid, e.start, e.target, bandOptions()).ok();
      setPillar(grid, cells, false);
      if (path) {
        e.pillar = std::move(cells);
        e.path_exists = true;
        break;
      }
    }
    set.scenarios.push_back(std::move(e));
  }
  return set;
}

}  // namespace mmh::eam_bench
