// The key registry: complete, consistent with deploy/config/default.yaml, and strict about
// unregistered keys (so that every key a service reads is caught by that service's tests).
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <set>

#include "config_test_files.hpp"
#include "mmh/common/config.hpp"
#include "mmh/common/config_registry.hpp"

using mmh::Config;
using mmh::KeySpec;
using mmh::KeyType;

namespace {

// The value of `key` in a YAML tree (an undefined node when absent).
YAML::Node at(YAML::Node node, const std::string& key) {
  size_t begin = 0;
  for (size_t dot = key.find('.');; dot = key.find('.', begin)) {
    const std::string part = key.substr(begin, dot == std::string::npos ? dot : dot - begin);
    if (!node.IsMap() || !node[part]) return YAML::Node(YAML::NodeType::Undefined);
    node.reset(node[part]);
    if (dot == std::string::npos) return node;
    begin = dot + 1;
  }
}

}  // namespace

TEST(ConfigRegistry, KeysAreUniqueDocumentedAndInTheirSection) {
  std::set<std::string> names, sections;
  for (const auto& s : mmh::configSections()) sections.insert(s.name);
  for (const KeySpec& k : mmh::configKeys()) {
    EXPECT_TRUE(names.insert(k.name).second) << "registered twice: " << k.name;
    EXPECT_FALSE(k.doc.empty()) << k.name;
    EXPECT_TRUE(sections.count(k.section())) << k.name << ": no section entry";
    if (k.type == KeyType::kEnum) {
      EXPECT_FALSE(k.allowed.empty()) << k.name;
    } else if (k.type != KeyType::kBool) {
      EXPECT_LE(k.min, k.max) << k.name;
    }
  }
}

TEST(ConfigRegistry, DefaultsAreValidValues) {
  // An empty file: every key read through its default (required ones are made present).
  YAML::Node root(YAML::NodeType::Map);
  for (const KeySpec& k : mmh::configKeys()) {
    YAML::Node node = root;
    const std::string& name = k.name;
    size_t begin = 0;
    for (size_t dot = name.find('.'); dot != std::string::npos; dot = name.find('.', begin)) {
      node.reset(node[name.substr(begin, dot - begin)]);
      begin = dot + 1;
    }
    node[name.substr(begin)] = YAML::Load(k.default_yaml);
  }
  const Config c = Config::fromString(YAML::Dump(root), "registry defaults");
  for (const KeySpec& k : mmh::configKeys()) {
    switch (k.type) {
      case KeyType::kDouble:
        EXPECT_NO_THROW(c.getDouble(k.name)) << k.name;
        break;
      case KeyType::kInt:
        EXPECT_NO_THROW(c.getInt(k.name)) << k.name;
        break;
      case KeyType::kBool:
        EXPECT_NO_THROW(c.getBool(k.name)) << k.name;
        break;
      case KeyType::kEnum:
        EXPECT_NO_THROW(c.getString(k.name)) << k.name;
        break;
      case KeyType::kVector3:
        EXPECT_NO_THROW(c.getVector3(k.name)) << k.name;
        break;
    }
  }
}

// default.yaml is written by hand (its comments explain the values); it must list every key with
// exactly the registry's default, so that the registry stays the one source of truth.
TEST(ConfigRegistry, DefaultYamlHoldsEveryKeyWithTheRegistryDefault) {
  const YAML::Node file = YAML::LoadFile(config_test::defaultYamlPath());
  for (const KeySpec& k : mmh::configKeys()) {
    const YAML::Node value = at(file, k.name);
    ASSERT_TRUE(value.IsDefined()) << k.name << " is not in default.yaml";
    const YAML::Node def = YAML::Load(k.default_yaml);
    switch (k.type) {
      case KeyType::kDouble:
        EXPECT_EQ(value.as<double>(), def.as<double>()) << k.name;
        break;
      case KeyType::kInt:
        EXPECT_EQ(value.as<long long>(), def.as<long long>()) << k.name;
        break;
      case KeyType::kBool:
        EXPECT_EQ(value.as<bool>(), def.as<bool>()) << k.name;
        break;
      case KeyType::kEnum:
        EXPECT_EQ(value.as<std::string>(), def.as<std::string>()) << k.name;
        break;
      case KeyType::kVector3:
        ASSERT_EQ(value.size(), 3u) << k.name;
        for (int i = 0; i < 3; ++i) EXPECT_EQ(value[i].as<double>(), def[i].as<double>()) << k.name;
        break;
    }
  }
}

TEST(ConfigRegistry, UnitsComeFromTheKeyNames) {
  EXPECT_EQ(mmh::registeredConfigKey("vehicle.max_vel_mps").unit(), "m/s");
  EXPECT_EQ(mmh::registeredConfigKey("vehicle.max_acc_mps2").unit(), "m/s^2");
  EXPECT_EQ(mmh::registeredConfigKey("map.inflation_m").unit(), "m");
  EXPECT_EQ(mmh::registeredConfigKey("sim.step_s").unit(), "s");
  EXPECT_EQ(mmh::registeredConfigKey("sim.max_yaw_rate_dps").unit(), "deg/s");
  EXPECT_EQ(mmh::registeredConfigKey("sim.depth.width_px").unit(), "px");
  EXPECT_EQ(mmh::registeredConfigKey("fpm.time_weight").unit(), "");
}

TEST(ConfigRegistry, ReadingAnUnregisteredKeyIsAProgrammingError) {
  const Config c = Config::fromString("vehicle: {max_vel_mps: 3.0, colour: red}\n");
  EXPECT_THROW(c.getDouble("vehicle.colour"), std::logic_error);
  EXPECT_THROW(mmh::registeredConfigKey("vehicle.colour"), std::logic_error);
  // ... and so is reading a key as another type than registered.
  EXPECT_THROW(c.getInt("vehicle.max_vel_mps"), std::logic_error);
}

TEST(ConfigRegistry, OptionalKeysTakeTheirDefault) {
  const Config c = Config::fromString("som: {time_weight: 500}\n");
  EXPECT_EQ(c.getDouble("som.time_weight"), 500.0);
  EXPECT_EQ(c.getInt("som.max_evaluations"), 60);  // missing: the registry's default
  EXPECT_THROW(c.getDouble("vehicle.max_vel_mps"), mmh::ConfigError);  // required
}

TEST(ConfigRegistry, NearestKeyByEditDistance) {
  EXPECT_EQ(mmh::nearestConfigKey("som.weight_corridr"), "som.weight_corridor");
  EXPECT_EQ(mmh::nearestConfigKey("arbitr.policy"), "arbiter.policy");
  EXPECT_EQ(mmh::nearestConfigKey("vehicel"), "vehicle");
  EXPECT_EQ(mmh::nearestConfigKey("sim.lidar.range"), "sim.lidar.range_m");
  EXPECT_EQ(mmh::nearestConfigKey("completely.unrelated_words"), "");
}
