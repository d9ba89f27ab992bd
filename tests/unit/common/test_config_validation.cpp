// Start-up validation of a whole file: unknown keys with a suggestion, missing keys, ranges.
#include <gtest/gtest.h>

#include "config_test_files.hpp"
#include "mmh/common/config_validation.hpp"

using mmh::Config;

namespace {

std::string problemsOf(const Config& c) {
  std::string all;
  for (const std::string& p : mmh::configProblems(c)) all += p + "\n";
  return all;
}

}  // namespace

TEST(ConfigValidation, TheShippedDefaultIsValid) {
  EXPECT_EQ(problemsOf(Config::loadFile(config_test::defaultYamlPath())), "");
  EXPECT_NO_THROW(mmh::validateConfig(Config::loadFile(config_test::defaultYamlPath())));
}

TEST(ConfigValidation, UnknownKeyIsRejectedWithTheNearestValidKey) {
  const Config c = config_test::defaultWith("som.weight_corridr", "1.0e5");
  EXPECT_NE(problemsOf(c).find("unknown key 'som.weight_corridr' in edited.yaml (did you mean "
                               "'som.weight_corridor'?)"),
            std::string::npos)
      << problemsOf(c);
  try {
    mmh::validateConfig(c);
    FAIL() << "accepted";
  } catch (const mmh::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("som.weight_corridor"), std::string::npos);
  }
}

TEST(ConfigValidation, UnknownSectionsAndNestedKeysAreRejected) {
  std::string p = problemsOf(config_test::defaultWith("vehicel", "{max_vel_mps: 3.0}"));
  EXPECT_NE(p.find("unknown key 'vehicel' in edited.yaml (did you mean 'vehicle'?)"),
            std::string::npos)
      << p;
  p = problemsOf(config_test::defaultWith("sim.depth.fov_deg", "80.0"));
  EXPECT_NE(p.find("unknown key 'sim.depth.fov_deg'"), std::string::npos) << p;
  EXPECT_NE(p.find("did you mean 'sim.depth.hfov_deg'?"), std::string::npos) << p;
  p = problemsOf(config_test::defaultWith("rotor_count", "4"));
  EXPECT_NE(p.find("unknown key 'rotor_count' in edited.yaml"), std::string::npos) << p;
  EXPECT_EQ(p.find("did you mean"), std::string::npos) << p;
}

TEST(ConfigValidation, OutOfRangeValueNamesTheKeyAndTheRange) {
  std::string p = problemsOf(config_test::defaultWith("vehicle.max_vel_mps", "120"));
  EXPECT_NE(p.find("edited.yaml: key 'vehicle.max_vel_mps' = 120 is outside the allowed range "
                   "[0.1, 50]"),
            std::string::npos)
      << p;
  p = problemsOf(config_test::defaultWith("mapping.delta_repeat", "0"));
  EXPECT_NE(p.find("'mapping.delta_repeat' = 0 is outside the allowed range [1, 16]"),
            std::string::npos)
      << p;
  p = problemsOf(config_test::defaultWith("geofence.max_m", "[30, 30, 2e6]"));
  EXPECT_NE(p.find("'geofence.max_m' element 2"), std::string::npos) << p;
  p = problemsOf(config_test::defaultWith("arbiter.policy", "fastest"));
  EXPECT_NE(p.find("'arbiter.policy' = 'fastest' is not one of: mmh, mmh-no-lazy"),
            std::string::npos)
      << p;
  p = problemsOf(config_test::defaultWith("eam.guide_warm_start", "sometimes"));
  EXPECT_NE(p.find("'eam.guide_warm_start' must be true or false"), std::string::npos) << p;
}

TEST(ConfigValidation, MissingRequiredKeysAreNamedOptionalOnesAreNot) {
  const Config c = Config::fromString("vehicle: {max_vel_mps: 3.0}\n", "partial.yaml");
  const std::string p = problemsOf(c);
  EXPECT_NE(p.find("partial.yaml: key 'vehicle.max_acc_mps2' is missing"), std::string::npos);
  EXPECT_NE(p.find("'arbiter.policy' is missing"), std::string::npos);
  EXPECT_EQ(p.find("'som."), std::string::npos) << "som keys are optional";
}
