// A synthetic, fully known map window for the command-line request tools: free space with
// vertical pillars given on the command line and/or a random forest (the benchmark generator),
// published as one LOCAL_MAP keyframe.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "mmh/common/cli.hpp"
#include "mmh/common/config.hpp"
#include "mmh/common/forest.hpp"
#include "mmh/common/voxel_grid.hpp"

namespace mmh::tools {

struct SceneOptions {
  std::string pillars;          // "x,y,r;x,y,r" (full-height cylinders)
  double forest_density = 0.0;  // obstacles per m^2 (0: none)
  int forest_seed = 1;
  bool no_map = false;  // publish no LOCAL_MAP at all
};

void addSceneOptions(ArgParser& parser, SceneOptions* options);

// Parses "x,y,r;..." into cylinders; false with a message if malformed.
bool parsePillars(const std::string& text, std::vector<Cylinder>* out, std::string* error);

// The window of the configuration (map.resolution_m, map.window_size_m, map.inflation_m)
// centred on `centre`, every cell known: occupied inside the scene's cylinders, else free.
// Throws ConfigError / std::invalid_argument with a message.
std::unique_ptr<VoxelGrid> buildScene(const SceneOptions& options, const Config& config,
                                      const Eigen::Vector3d& centre);

}  // namespace mmh::tools
