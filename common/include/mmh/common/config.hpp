// Deployment configuration: one YAML file (deploy/config/default.yaml) read with yaml-cpp.
// Every getter validates the value and fails with a message naming the file, the key and the
// allowed range, so a bad file stops a service at start-up instead of in the air.
#pragma once

#include <yaml-cpp/yaml.h>
#include <Eigen/Core>
#include <stdexcept>
#include <string>

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
  // Keys are dotted paths, e.g. "vehicle.max_vel_mps". Ranges are inclusive.
  double getDouble(const std::string& key, double min, double max) const;
  int getInt(const std::string& key, int min, int max) const;
  bool getBool(const std::string& key) const;
  std::string getString(const std::string& key) const;
  Eigen::Vector3d getVector3(const std::string& key, double min, double max) const;
  Eigen::Vector3i getVector3i(const std::string& key, int min, int max) const;

  const std::string& source() const { return source_; }

 private:
  YAML::Node lookup(const std::string& key) const;
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

  YAML::Node root_;
  std::string source_;
};

}  // namespace mmh
