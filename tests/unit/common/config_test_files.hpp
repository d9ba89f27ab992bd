// Helpers of the configuration tests: the shipped default.yaml, with single values changed.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

#include "mmh/common/config.hpp"

namespace config_test {

inline std::string defaultYamlPath() {
  return std::string(MMH_SOURCE_DIR) + "/deploy/config/default.yaml";
}

// default.yaml with `key` (dotted) set to the YAML value `value_yaml`.
inline mmh::Config defaultWith(const std::string& key, const std::string& value_yaml) {
  YAML::Node root = YAML::LoadFile(defaultYamlPath());
  YAML::Node node = root;
  size_t begin = 0;
  for (size_t dot = key.find('.'); dot != std::string::npos; dot = key.find('.', begin)) {
    node.reset(node[key.substr(begin, dot - begin)]);
    begin = dot + 1;
  }
  node[key.substr(begin)] = YAML::Load(value_yaml);
  return mmh::Config::fromString(YAML::Dump(root), "edited.yaml");
}

}  // namespace config_test
