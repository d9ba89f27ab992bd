// --set key=value of mmh-stack and mmh-bench: overrides reach the configuration, unknown keys
// and sections are refused with the key named, and the options are taken out of argv.
#include <gtest/gtest.h>

#include <cstring>

#include "config_overrides.hpp"

namespace mmh {
namespace {

const char* kYaml = R"(
vehicle:
  max_vel_mps: 3.0
  radius_m: 0.15
sim:
  depth:
    range_m: 4.5
geofence:
  min_m: [-30, -30, 0.3]
)";

TEST(ConfigOverrides, ReplaceExistingKeys) {
  const Config c = applyConfigOverrides(
      kYaml, "test.yaml",
      {"vehicle.max_vel_mps=2.5", "sim.depth.range_m=6", "geofence.min_m=[-5, -5, 0.5]"});
  EXPECT_DOUBLE_EQ(c.getDouble("vehicle.max_vel_mps"), 2.5);
  EXPECT_DOUBLE_EQ(c.getDouble("vehicle.radius_m"), 0.15);
  EXPECT_DOUBLE_EQ(c.getDouble("sim.depth.range_m"), 6.0);
  EXPECT_EQ(c.getVector3("geofence.min_m"), Eigen::Vector3d(-5, -5, 0.5));
}

TEST(ConfigOverrides, ARegisteredKeyTheFileOmitsIsAdded) {
  // som.first_step is optional: a file may leave it out and still have it set.
  const Config c =
      applyConfigOverrides(kYaml, "test.yaml", {"som.first_step=0.5", "vehicle.max_acc_mps2=4"});
  EXPECT_DOUBLE_EQ(c.getDouble("som.first_step"), 0.5);
  EXPECT_DOUBLE_EQ(c.getDouble("vehicle.max_acc_mps2"), 4.0);
  EXPECT_DOUBLE_EQ(c.getDouble("vehicle.max_vel_mps"), 3.0);
}

TEST(ConfigOverrides, UnknownKeysSectionsAndMalformedAssignmentsAreRefused) {
  auto message = [](const std::string& assignment) {
    try {
      applyConfigOverrides(kYaml, "test.yaml", {assignment});
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("vehicle.max_speed=2").find("'vehicle.max_speed' does not exist"),
            std::string::npos);
  EXPECT_NE(message("nosuch.key=1").find("'nosuch.key' does not exist"), std::string::npos);
  EXPECT_NE(message("vehicle.max_vel_mps.x=1").find("does not exist"), std::string::npos);
  EXPECT_NE(message("sim=1").find("is a section"), std::string::npos);
  EXPECT_NE(message("vehicle.max_vel_mps").find("expected key=value"), std::string::npos);
}

TEST(ConfigOverrides, SetOptionsAreTakenOutOfTheArguments) {
  std::vector<std::string> storage = {"prog", "--set", "a.b=1", "--json", "--set=c.d=2", "--x"};
  std::vector<char*> argv;
  for (std::string& s : storage) argv.push_back(s.data());
  argv.push_back(nullptr);
  int argc = static_cast<int>(storage.size());
  const std::vector<std::string> sets = takeSetOptions(&argc, argv.data());
  EXPECT_EQ(sets, (std::vector<std::string>{"a.b=1", "c.d=2"}));
  ASSERT_EQ(argc, 3);
  EXPECT_STREQ(argv[1], "--json");
  EXPECT_STREQ(argv[2], "--x");
  EXPECT_EQ(argv[3], nullptr);
}

}  // namespace
}  // namespace mmh
