// The registry of every configuration key: name, type, allowed range or values, default and one
// line of documentation. It is the one source of truth: Config's getters take the range and the
// default from here, start-up validation rejects keys that are not here, and
// docs/configuration.md is generated from it (mmh-config-doc).
#pragma once

#include <string>
#include <vector>

namespace mmh {

enum class KeyType { kDouble, kInt, kBool, kEnum, kVector3 };

struct KeySpec {
  std::string name;  // dotted path, e.g. "vehicle.max_vel_mps"
  KeyType type = KeyType::kDouble;
  double min = 0.0;  // inclusive range: kDouble, kInt, each kVector3 element
  double max = 0.0;
  std::vector<std::string> allowed;  // kEnum: the allowed values
  // The default as YAML text ("3.0", "[-30.0, -30.0, 0.3]", "mmh"): the value of an optional key
  // that a file omits, and the value deploy/config/default.yaml holds (a test checks both agree).
  std::string default_yaml;
  bool required = true;  // a required key must be in the file (safety-relevant values)
  std::string doc;

  std::string section() const;    // the first part of the name: "sim" for "sim.depth.range_m"
  std::string unit() const;       // from the name's suffix: "m/s" for _mps, "" for none
  std::string typeName() const;   // "double", "int", "bool", "enum", "vector3"
  std::string rangeText() const;  // "[0.1, 50]", "true / false", "mmh | ego | ..."
};

struct SectionSpec {
  std::string name;
  std::string doc;
};

// Every key, in the order of deploy/config/default.yaml (the documentation's order).
const std::vector<KeySpec>& configKeys();
// The top-level sections, in the same order.
const std::vector<SectionSpec>& configSections();

// nullptr when the key is not registered.
const KeySpec* findConfigKey(const std::string& name);
// Throws std::logic_error for an unregistered key: reading one is a programming error, and every
// test that loads a service's parameters then fails.
const KeySpec& registeredConfigKey(const std::string& name);
// True when some registered key lies below this dotted prefix ("sim", "sim.depth").
bool isConfigSection(const std::string& prefix);
// The registered key nearest to `name` by edit distance ("" when none is close enough to be a
// plausible misspelling).
std::string nearestConfigKey(const std::string& name);

}  // namespace mmh
