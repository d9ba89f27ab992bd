// Constraints between keys (often of different services): each is rejected with both keys named.
#include <gtest/gtest.h>

#include "config_test_files.hpp"
#include "mmh/common/config_constraints.hpp"

namespace {

// The one violation of default.yaml with `key` set to `value`.
std::string violationWith(const std::string& key, const std::string& value) {
  const auto v = mmh::constraintViolations(config_test::defaultWith(key, value));
  EXPECT_EQ(v.size(), 1u) << key << ": " << ::testing::PrintToString(v);
  return v.empty() ? "" : v.front();
}

void expectNames(const std::string& message, const std::string& a, const std::string& b) {
  EXPECT_NE(message.find("'" + a + "'"), std::string::npos) << message;
  EXPECT_NE(message.find(b), std::string::npos) << message;
  EXPECT_NE(message.find("edited.yaml"), std::string::npos) << message;
}

}  // namespace

TEST(ConfigConstraints, TheShippedDefaultSatisfiesAll) {
  EXPECT_TRUE(
      mmh::constraintViolations(mmh::Config::loadFile(config_test::defaultYamlPath())).empty());
}

TEST(ConfigConstraints, StartEscapeClearanceStaysOutsideTheArbiterCheck) {
  // 0.28 >= 0.25 + 0.02 holds; 0.26 does not.
  expectNames(violationWith("som.start_escape_clearance_m", "0.26"), "som.start_escape_clearance_m",
              "arbiter.check_inflation_m");
  expectNames(violationWith("eam.start_escape_clearance_m", "0.26"), "eam.start_escape_clearance_m",
              "arbiter.check_inflation_m");
  // The same from the other side: a larger arbiter check margin. It breaks both planners'.
  EXPECT_EQ(mmh::constraintViolations(config_test::defaultWith("arbiter.check_inflation_m", "0.27"))
                .size(),
            2u);
}

TEST(ConfigConstraints, ArbiterCheckInflationWithinTheMapInflation) {
  expectNames(violationWith("map.inflation_m", "0.2"), "arbiter.check_inflation_m",
              "map.inflation_m");
}

TEST(ConfigConstraints, AnswerDeadlineBeforeTheReplanLead) {
  expectNames(violationWith("arbiter.answer_deadline_s", "0.06"), "arbiter.answer_deadline_s",
              "arbiter.replan_lead_s");
  // A zero lead (trajectories take effect at once) does not bound the deadline.
  EXPECT_TRUE(
      mmh::constraintViolations(config_test::defaultWith("arbiter.replan_lead_s", "0.0")).empty());
}

TEST(ConfigConstraints, EamsSecondPlanHasTheFinerKnotSpan) {
  expectNames(violationWith("eam.fine_knot_span_s", "0.2"), "eam.fine_knot_span_s",
              "eam.knot_span_s");
  EXPECT_TRUE(
      mmh::constraintViolations(config_test::defaultWith("eam.fine_knot_span_s", "0.1")).empty());
}

TEST(ConfigConstraints, GeofenceIsANonEmptyBox) {
  expectNames(violationWith("geofence.max_m", "[30, 30, 0.2]"), "geofence.max_m", "geofence.min_m");
}

TEST(ConfigConstraints, MapWindowCoversThePlanningRange) {
  expectNames(violationWith("arbiter.planning_horizon_s", "6.0"), "map.window_size_m",
              "arbiter.planning_horizon_s");
}

TEST(ConfigConstraints, FullSpeedStopsWithinTheSensorRange) {
  // 3 m/s at 2 m/s^2: 2.25 m + 3 x 0.55 s = 3.9 m <= 4.5 m. At 1 m/s^2: 6.15 m.
  expectNames(violationWith("vehicle.max_acc_mps2", "1.0"), "vehicle.max_acc_mps2",
              "awareness.sensor_range_m");
  expectNames(violationWith("awareness.sensor_range_m", "3.5"), "vehicle.max_vel_mps",
              "awareness.sensor_range_m");
}

TEST(ConfigConstraints, LidarElevationsAndOccupancyThreshold) {
  expectNames(violationWith("sim.lidar.vmax_deg", "-8.0"), "sim.lidar.vmax_deg",
              "sim.lidar.vmin_deg");
  expectNames(violationWith("mapping.occupancy_threshold", "0.1"), "mapping.occupancy_threshold",
              "mapping.clamp_min");
  expectNames(violationWith("mapping.occupancy_threshold", "0.98"), "mapping.occupancy_threshold",
              "mapping.clamp_max");
}

TEST(ConfigConstraints, PartialConfigsAreCheckedOnWhatTheyHold) {
  // No arbiter section: the escape constraints cannot be evaluated and are not reported.
  const auto c = mmh::Config::fromString("som: {start_escape_clearance_m: 0.1}\n");
  EXPECT_TRUE(mmh::constraintViolations(c).empty());
  EXPECT_THROW(mmh::checkConfigConstraints(config_test::defaultWith("map.inflation_m", "0.2")),
               mmh::ConfigError);
}
