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
      "vehicle:\n  max_vel_mps: 3.0\narbiter:\n  policy: som\n  defer_far_collisions: true\n"
      "eam:\n  max_restarts: 4\ngeofence:\n  min_m: [-1, -2.5, 0]\n");
  EXPECT_DOUBLE_EQ(c.getDouble("vehicle.max_vel_mps"), 3.0);
  EXPECT_EQ(c.getString("arbiter.policy"), "som");
  EXPECT_TRUE(c.getBool("arbiter.defer_far_collisions"));
  EXPECT_EQ(c.getInt("eam.max_restarts"), 4);
  EXPECT_TRUE(c.getVector3("geofence.min_m").isApprox(Eigen::Vector3d(-1, -2.5, 0)));
  EXPECT_TRUE(c.has("arbiter.policy"));
  EXPECT_FALSE(c.has("vehicle.nothing"));
}

TEST(Config, ErrorsNameTheKeyAndTheRange) {
  Config c = Config::fromString(
      "vehicle:\n  max_vel_mps: 120\n  max_acc_mps2: abc\n"
      "geofence:\n  min_m: [1, 2]\neam:\n  max_restarts: 2.5\n",
      "test.yaml");
  std::string e = errorOf([&] { c.getDouble("vehicle.max_vel_mps"); });
  EXPECT_NE(e.find("test.yaml"), std::string::npos);
  EXPECT_NE(e.find("vehicle.max_vel_mps"), std::string::npos);
  EXPECT_NE(e.find("[0.1, 50]"), std::string::npos);
  e = errorOf([&] { c.getDouble("vehicle.radius_m"); });
  EXPECT_NE(e.find("vehicle.radius_m"), std::string::npos);
  EXPECT_NE(e.find("missing"), std::string::npos);
  e = errorOf([&] { c.getDouble("vehicle.max_acc_mps2"); });
  EXPECT_NE(e.find("must be a number"), std::string::npos);
  e = errorOf([&] { c.getVector3("geofence.min_m"); });
  EXPECT_NE(e.find("3 numbers"), std::string::npos);
  e = errorOf([&] { c.getInt("eam.max_restarts"); });
  EXPECT_NE(e.find("must be an integer"), std::string::npos);
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
  EXPECT_GT(c.getDouble("vehicle.max_vel_mps"), 0.0);
}
