// Options every node executable takes: --lcm-url, --prefix, --config, --log-level; and loading
// of the configuration with a clear start-up error.
#pragma once

#include <string>

#include "mmh/common/cli.hpp"
#include "mmh/common/config.hpp"

namespace mmh {

struct NodeOptions {
  std::string lcm_url;      // empty: LCM_DEFAULT_URL or LCM's default (ttl=0, this host only)
  std::string prefix;       // channel prefix, e.g. "UAV1_"
  std::string config_path;  // empty: $MMH_CONFIG or deploy/config/default.yaml of the source tree
  std::string log_level = "info";
};

void addNodeOptions(ArgParser& parser, NodeOptions* options);
// Applies the log level, loads the config and validates it against the key registry (throws
// ConfigError listing every problem).
Config loadNodeConfig(const NodeOptions& options);
std::string defaultConfigPath();

}  // namespace mmh
