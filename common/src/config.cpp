#include "mmh/common/config.hpp"

#include <cmath>
#include <sstream>

namespace mmh {
namespace {

std::string formatRange(double min, double max) {
  std::ostringstream s;
  s << "[" << min << ", " << max << "]";
  return s.str();
}

}  // namespace

Config Config::loadFile(const std::string& path) {
  Config c;
  c.source_ = path;
  try {
    c.root_ = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw ConfigError(path + ": cannot open the configuration file");
  } catch (const YAML::Exception& e) {
    throw ConfigError(path + ": not valid YAML: " + e.what());
  }
  if (!c.root_.IsMap()) throw ConfigError(path + ": the top level must be a mapping of sections");
  return c;
}

Config Config::fromString(const std::string& yaml_text, const std::string& source) {
  Config c;
  c.source_ = source;
  try {
    c.root_ = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(source + ": not valid YAML: " + e.what());
  }
  if (!c.root_.IsMap()) throw ConfigError(source + ": the top level must be a mapping of sections");
  return c;
}

void Config::fail(const std::string& key, const std::string& what) const {
  throw ConfigError(source_ + ": key '" + key + "' " + what);
}

YAML::Node Config::lookup(const std::string& key) const {
  // yaml-cpp's operator[] on a const node does not insert; walk the dotted path.
  std::stringstream path(key);
  std::string part;
  std::vector<YAML::Node> chain{root_};
  while (std::getline(path, part, '.')) {
    const YAML::Node& parent = chain.back();
    if (!parent.IsMap() || !parent[part]) fail(key, "is missing");
    chain.push_back(parent[part]);
  }
  return chain.back();
}

bool Config::has(const std::string& key) const {
  std::stringstream path(key);
  std::string part;
  std::vector<YAML::Node> chain{root_};
  while (std::getline(path, part, '.')) {
    const YAML::Node& parent = chain.back();
    if (!parent.IsMap() || !parent[part]) return false;
    chain.push_back(parent[part]);
  }
  return true;
}

const KeySpec& Config::spec(const std::string& key, KeyType expected) {
  const KeySpec& s = registeredConfigKey(key);
  if (s.type != expected) {
    throw std::logic_error("configuration key '" + key + "' is registered as " + s.typeName());
  }
  return s;
}

YAML::Node Config::valueOf(const KeySpec& spec) const {
  if (!spec.required && !has(spec.name)) return YAML::Load(spec.default_yaml);
  return lookup(spec.name);
}

double Config::getDouble(const std::string& key) const {
  const KeySpec& s = spec(key, KeyType::kDouble);
  const YAML::Node n = valueOf(s);
  double v = 0.0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    fail(key, "must be a number, allowed range " + formatRange(s.min, s.max));
  }
  if (!std::isfinite(v) || v < s.min || v > s.max) {
    std::ostringstream out;
    out << "= " << v << " is outside the allowed range " << formatRange(s.min, s.max);
    fail(key, out.str());
  }
  return v;
}

int Config::getInt(const std::string& key) const {
  const KeySpec& s = spec(key, KeyType::kInt);
  const YAML::Node n = valueOf(s);
  long long v = 0;
  try {
    v = n.as<long long>();
  } catch (const YAML::Exception&) {
    fail(key, "must be an integer, allowed range " + formatRange(s.min, s.max));
  }
  if (v < s.min || v > s.max) {
    fail(key,
         "= " + std::to_string(v) + " is outside the allowed range " + formatRange(s.min, s.max));
  }
  return static_cast<int>(v);
}

bool Config::getBool(const std::string& key) const {
  const YAML::Node n = valueOf(spec(key, KeyType::kBool));
  try {
    return n.as<bool>();
  } catch (const YAML::Exception&) {
    fail(key, "must be true or false");
  }
}

std::string Config::getString(const std::string& key) const {
  const KeySpec& s = spec(key, KeyType::kEnum);
  const YAML::Node n = valueOf(s);
  if (!n.IsScalar()) fail(key, "must be one of: " + s.rangeText());
  const std::string v = n.as<std::string>();
  for (const std::string& allowed : s.allowed) {
    if (v == allowed) return v;
  }
  fail(key, "= '" + v + "' is not one of: " + s.rangeText());
}

Eigen::Vector3d Config::getVector3(const std::string& key) const {
  const KeySpec& s = spec(key, KeyType::kVector3);
  const YAML::Node n = valueOf(s);
  if (!n.IsSequence() || n.size() != 3) fail(key, "must be a list of 3 numbers");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    try {
      v[i] = n[i].as<double>();
    } catch (const YAML::Exception&) {
      fail(key, "must be a list of 3 numbers");
    }
    if (!std::isfinite(v[i]) || v[i] < s.min || v[i] > s.max) {
      std::ostringstream out;
      out << "element " << i << " = " << v[i] << " is outside the allowed range "
          << formatRange(s.min, s.max);
      fail(key, out.str());
    }
  }
  return v;
}

}  // namespace mmh
