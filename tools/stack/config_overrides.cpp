#include "config_overrides.hpp"

#include <yaml-cpp/yaml.h>

#include <cstring>
#include <fstream>
#include <sstream>

#include "mmh/common/config_registry.hpp"
#include "mmh/common/config_validation.hpp"

namespace mmh {
namespace {

[[noreturn]] void unknownKey(const std::string& key, const std::string& source) {
  const std::string nearest = nearestConfigKey(key);
  throw ConfigError("--set: key '" + key + "' does not exist in " + source +
                    (nearest.empty() ? "" : " (did you mean '" + nearest + "'?)"));
}

}  // namespace

std::vector<std::string> takeSetOptions(int* argc, char** argv) {
  std::vector<std::string> values;
  int kept = 1;
  for (int i = 1; i < *argc; ++i) {
    const char* arg = argv[i];
    if (std::strcmp(arg, "--set") == 0 && i + 1 < *argc) {
      values.emplace_back(argv[++i]);
    } else if (std::strncmp(arg, "--set=", 6) == 0) {
      values.emplace_back(arg + 6);
    } else {
      argv[kept++] = argv[i];
    }
  }
  *argc = kept;
  argv[kept] = nullptr;
  return values;
}

Config applyConfigOverrides(const std::string& yaml_text, const std::string& source,
                            const std::vector<std::string>& assignments) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(source + ": not valid YAML: " + e.what());
  }
  for (const std::string& assignment : assignments) {
    const size_t eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw ConfigError("--set " + assignment + ": expected key=value");
    }
    const std::string key = assignment.substr(0, eq), text = assignment.substr(eq + 1);
    std::vector<std::string> parts;
    std::stringstream path(key);
    for (std::string part; std::getline(path, part, '.');) parts.push_back(part);
    // A registered key the file omits (an optional one) is added; any other missing key is
    // refused. Walk with const lookups: yaml-cpp's non-const operator[] would create it.
    const bool registered = findConfigKey(key) != nullptr;
    YAML::Node parent = root;
    for (size_t i = 0; i + 1 < parts.size(); ++i) {
      const YAML::Node& view = parent;
      if (!view.IsMap() || !view[parts[i]]) {
        if (!registered || (view && !view.IsMap())) unknownKey(key, source);
        parent[parts[i]] = YAML::Node(YAML::NodeType::Map);
      }
      parent.reset(parent[parts[i]]);
    }
    const YAML::Node& view = parent;
    if (parts.empty() || !view.IsMap() || (!view[parts.back()] && !registered)) {
      unknownKey(key, source);
    }
    if (view[parts.back()] && view[parts.back()].IsMap()) {
      throw ConfigError("--set: key '" + key + "' is a section; set one of its keys");
    }
    YAML::Node value;
    try {
      value = YAML::Load(text);
    } catch (const YAML::Exception& e) {
      throw ConfigError("--set " + assignment + ": the value is not valid YAML: " + e.what());
    }
    parent[parts.back()] = value;
  }
  std::ostringstream out;
  out << root;
  return Config::fromString(out.str(), source + " with --set");
}

Config loadConfigWithOverrides(const NodeOptions& options,
                               const std::vector<std::string>& assignments) {
  Config config = loadNodeConfig(options);
  if (assignments.empty()) return config;
  std::ifstream in(config.source());
  std::stringstream text;
  text << in.rdbuf();
  // The overridden file passes the same start-up validation as the file itself.
  Config overridden = applyConfigOverrides(text.str(), config.source(), assignments);
  validateConfig(overridden);
  return overridden;
}

}  // namespace mmh
