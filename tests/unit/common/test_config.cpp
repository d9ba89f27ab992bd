#include <gtest/gtest.h>

#include "mmh/common/config.hpp"

using mmh::Config;
using mmh::ConfigError;

namespace {

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Config, ReadsTypedValues) {
  Config c = Config::fromString(
      "vehicle:\n  max_vel_mps: 3.0\n  name: quad\n  armed: true\n  pieces: 4\n"
      "geofence:\n  min_m: [-1, -2.5, 0]\n");
  EXPECT_DOUBLE_EQ(c.getDouble("vehicle.max_vel_mps", 0.1, 50), 3.0);
  EXPECT_EQ(c.getString("vehicle.name"), "quad");
  EXPECT_TRUE(c.getBool("vehicle.armed"));
  EXPECT_EQ(c.getInt("vehicle.pieces", 1, 10), 4);
  EXPECT_TRUE(c.getVector3("geofence.min_m", -100, 100).isApprox(Eigen::Vector3d(-1, -2.5, 0)));
  EXPECT_TRUE(c.has("vehicle.name"));
  EXPECT_FALSE(c.has("vehicle.nothing"));
}

TEST(Config, ErrorsNameTheKeyAndTheRange) {
  Config c =
      Config::fromString("vehicle:\n  max_vel_mps: 120\n  bad: abc\n  list: [1, 2]\n", "test.yaml");
  std::string e = errorOf([&] { c.getDouble("vehicle.max_vel_mps", 0.1, 50); });
  EXPECT_NE(e.find("test.yaml"), std::string::npos);
  EXPECT_NE(e.find("vehicle.max_vel_mps"), std::string::npos);
  EXPECT_NE(e.find("[0.1, 50]"), std::string::npos);
  e = errorOf([&] { c.getDouble("vehicle.missing_m", 0, 1); });
  EXPECT_NE(e.find("vehicle.missing_m"), std::string::npos);
  EXPECT_NE(e.find("missing"), std::string::npos);
  e = errorOf([&] { c.getDouble("vehicle.bad", 0, 1); });
  EXPECT_NE(e.find("must be a number"), std::string::npos);
  e = errorOf([&] { c.getVector3("vehicle.list", 0, 10); });
  EXPECT_NE(e.find("3 numbers"), std::string::npos);
  e = errorOf([&] { c.getInt("vehicle.max_vel_mps", 0, 10); });
  EXPECT_NE(e.find("outside"), std::string::npos);
}

TEST(Config, CorruptFilesFailClearly) {
  EXPECT_NE(errorOf([] { Config::fromString("a: [1, 2\n"); }).find("not valid YAML"),
            std::string::npos);
  EXPECT_NE(errorOf([] { Config::fromString("- just\n- a list\n"); }).find("mapping"),
            std::string::npos);
  EXPECT_NE(errorOf([] { Config::loadFile("/nonexistent/mmh.yaml"); }).find("cannot open"),
            std::string::npos);
}

TEST(Config, ShippedDefaultLoads) {
  Config c = Config::loadFile(std::string(MMH_SOURCE_DIR) + "/deploy/config/default.yaml");
  EXPECT_GT(c.getDouble("vehicle.max_vel_mps", 0.1, 50), 0.0);
}
