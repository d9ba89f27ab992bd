#include "mmh/common/node_options.hpp"

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "mmh/common/config_validation.hpp"
#include "mmh/common/log.hpp"

#ifndef MMH_DEFAULT_CONFIG
#define MMH_DEFAULT_CONFIG "deploy/config/default.yaml"
#endif

namespace mmh {

// Without $MMH_CONFIG: an executable installed in MMH_INSTALL_BINDIR (/usr/bin from the Debian
// package) reads the installed configuration (/etc/mmh/mmh.yaml), one of a build tree the
// source tree's deploy/config/default.yaml.
static std::string builtinConfigPath() {
#if defined(MMH_INSTALL_BINDIR) && defined(MMH_INSTALLED_CONFIG)
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec && exe.parent_path() == std::filesystem::path(MMH_INSTALL_BINDIR))
    return MMH_INSTALLED_CONFIG;
#endif
  return MMH_DEFAULT_CONFIG;
}

std::string defaultConfigPath() {
  const char* env = std::getenv("MMH_CONFIG");
  return env && *env ? env : builtinConfigPath();
}

void addNodeOptions(ArgParser& parser, NodeOptions* options) {
  parser.addString("--lcm-url", &options->lcm_url,
                   "LCM URL (default: $LCM_DEFAULT_URL, else udpm://239.255.76.67:7667?ttl=0)");
  parser.addString("--prefix", &options->prefix, "channel prefix, e.g. UAV1_");
  parser.addString("--config", &options->config_path,
                   "configuration file (default: $MMH_CONFIG or " + builtinConfigPath() + ")");
  parser.addString("--log-level", &options->log_level, "debug, info, warn or error");
}

Config loadNodeConfig(const NodeOptions& options) {
  if (options.log_level == "debug")
    setLogLevel(LogLevel::kDebug);
  else if (options.log_level == "warn")
    setLogLevel(LogLevel::kWarn);
  else if (options.log_level == "error")
    setLogLevel(LogLevel::kError);
  else
    setLogLevel(LogLevel::kInfo);
  Config config =
      Config::loadFile(options.config_path.empty() ? defaultConfigPath() : options.config_path);
  // Once per node, on the whole file: a misspelt key would otherwise be ignored and its service
  // would run on another value.
  validateConfig(config);
  return config;
}

}  // namespace mmh
