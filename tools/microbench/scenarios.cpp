#include "scenarios.hpp"

#include <cmath>
#include <random>

#include "mmh/common/grid_astar.hpp"

namespace mmh {

std::vector<PlanningScenario> makeForestScenarios(const ScenarioSpec& spec) {
  std::vector<PlanningScenario> out;
  std::mt19937_64 rng(spec.seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), angle(-M_PI, M_PI);
  GridAStar astar;
  for (int m = 0; m < spec.maps; ++m) {
    ForestSpec forest_spec;
    forest_spec.density_per_m2 = spec.density_per_m2;
    forest_spec.seed = spec.seed * 1000 + m;
    auto forest = std::make_shared<const std::vector<Cylinder>>(generateForest(forest_spec));
    // One window per map, centred on the middle of the world; starts and targets fall inside.
    const Eigen::Vector3d centre(0.0, 0.0, spec.altitude_m);
    const Eigen::Vector3d lo = centre - 0.5 * spec.window_m;
    auto grid = std::make_shared<VoxelGrid>(
        spec.resolution_m,
        Eigen::Vector3i(static_cast<int>(std::floor(lo.x() / spec.resolution_m)),
                        static_cast<int>(std::floor(lo.y() / spec.resolution_m)),
                        static_cast<int>(std::floor(lo.z() / spec.resolution_m))),
        (spec.window_m / spec.resolution_m).array().round().cast<int>().matrix());
    rasterizeForest(*forest, *grid);
    grid->setInflationRadius(spec.inflation_m);
    int made = 0;
    for (int attempt = 0; made < spec.per_map && attempt < 10000; ++attempt) {
      // Start and target both inside the window with a 1 m margin, free of inflated obstacles.
      const double half = 0.5 * spec.window_m.x() - 1.0 - 0.5 * spec.target_distance_m;
      const Eigen::Vector3d mid(half * u(rng), half * u(rng), spec.altitude_m);
      const double a = angle(rng);
      const Eigen::Vector3d dir(std::cos(a), std::sin(a), 0.0);
      const Eigen::Vector3d start = mid - 0.5 * spec.target_distance_m * dir;
      const Eigen::Vector3d target = mid + 0.5 * spec.target_distance_m * dir;
      if (grid->isBlockedPoint(start) || grid->isBlockedPoint(target)) continue;
      PlanningScenario s;
      s.grid = grid;
      s.forest = forest;
      s.start = start;
      s.target = target;
      s.map_seed = forest_spec.seed;
      AStarOptions options;
      options.min_bound = Eigen::Vector3d(-1e9, -1e9, 0.3);
      options.max_bound = Eigen::Vector3d(1e9, 1e9, 2.7);
      s.path_exists = astar.search(*grid, start, target, options).ok();
      out.push_back(s);
      ++made;
    }
  }
  return out;
}

}  // namespace mmh
