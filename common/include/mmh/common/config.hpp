// Deployment configuration: one YAML file (deploy/config/default.yaml) read with yaml-cpp.
// Every key is registered (mmh/common/config_registry.hpp) with its type, allowed range and
// default; the getters check the value against it and fail with a message naming the file, the
// key and the range, so a bad file stops a service at start-up instead of in the air.
#pragma once

#include <yaml-cpp/yaml.h>
#include <Eigen/Core>
#include <stdexcept>
#include <string>

#include "mmh/common/config_registry.hpp"

namespace mmh {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Config {
 public:
  Config() = default;
  static Config loadFile(const std::string& path);
  static Config fromString(const std::string& yaml_text, const std::string& source = "<string>");

  bool has(const std::string& key) const;
  // Keys are dotted paths, e.g. "vehicle.max_vel_mps", and must be registered (an unregistered
  // key throws std::logic_error). A missing optional key yields the registry's default.
  double getDouble(const std::string& key) const;
  int getInt(const std::string& key) const;
  bool getBool(const std::string& key) const;
  std::string getString(const std::string& key) const;  // an enum key: one of its values
  Eigen::Vector3d getVector3(const std::string& key) const;

  const std::string& source() const { return source_; }
  const YAML::Node& root() const { return root_; }

 private:
  // The registered key; std::logic_error when it is unregistered or of another type.
  static const KeySpec& spec(const std::string& key, KeyType expected);
  // The key's node, or its default's when an optional key is missing.
  YAML::Node valueOf(const KeySpec& spec) const;
  YAML::Node lookup(const std::string& key) const;
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

  YAML::Node root_;
  std::string source_;
};

}  // namespace mmh
