#include "scene.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mmh::tools {

void addSceneOptions(ArgParser& parser, SceneOptions* options) {
  parser.addString("--map-pillars", &options->pillars,
                   "pillars in the map window: \"x,y,radius;x,y,radius\" (m)");
  parser.addDouble("--map-forest", &options->forest_density,
                   "random forest in the window, obstacles per m^2 (0: none)");
  parser.addInt("--map-seed", &options->forest_seed, "seed of the random forest");
  parser.addFlag("--no-map", &options->no_map, "publish no LOCAL_MAP");
}

bool parsePillars(const std::string& text, std::vector<Cylinder>* out, std::string* error) {
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ';')) {
    if (item.empty()) continue;
    Eigen::Vector3d v;
    if (!parseVector3(item, &v) || !(v.z() > 0.0)) {
      *error = "bad pillar '" + item + "' (want x,y,radius with radius > 0)";
      return false;
    }
    Cylinder c;
    c.center = v.head<2>();
    c.radius = v.z();
    c.z_min = -100.0;
    c.z_max = 100.0;
    out->push_back(c);
  }
  return true;
}

std::unique_ptr<VoxelGrid> buildScene(const SceneOptions& options, const Config& config,
                                      const Eigen::Vector3d& centre) {
  const double res = config.getDouble("map.resolution_m");
  const Eigen::Vector3d size_m = config.getVector3("map.window_size_m");
  const double inflation = config.getDouble("map.inflation_m");
  std::vector<Cylinder> cylinders;
  std::string error;
  if (!parsePillars(options.pillars, &cylinders, &error)) throw std::invalid_argument(error);
  if (options.forest_density > 0.0) {
    ForestSpec spec;
    spec.density_per_m2 = options.forest_density;
    spec.seed = static_cast<uint64_t>(options.forest_seed);
    for (const Cylinder& c : generateForest(spec)) cylinders.push_back(c);
  }
  const Eigen::Vector3d lo = centre - 0.5 * size_m;
  auto grid =
      std::make_unique<VoxelGrid>(res,
                                  Eigen::Vector3i(static_cast<int>(std::floor(lo.x() / res)),
                                                  static_cast<int>(std::floor(lo.y() / res)),
                                                  static_cast<int>(std::floor(lo.z() / res))),
                                  (size_m / res).array().round().cast<int>().matrix());
  rasterizeForest(cylinders, *grid);
  grid->setInflationRadius(inflation);
  return grid;
}

}  // namespace mmh::tools
