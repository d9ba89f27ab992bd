// Missions: reading waypoints (list and YAML), the rule of arrival, the sequencer's progression,
// and the geofence message that names its keys.
#include <gtest/gtest.h>

#include "mmh/common/geofence.hpp"
#include "mmh/common/mission.hpp"

using Eigen::Vector3d;
using mmh::MissionError;
using mmh::MissionRules;
using mmh::MissionSequencer;
using mmh::Waypoint;

TEST(Mission, AWaypointListPassesEveryWaypointButTheLast) {
  const MissionRules rules;
  const auto w = mmh::parseWaypointList(" 1,2,1.2; 3, 4, 1.5 ;5,6,1.0;", rules);
  ASSERT_EQ(w.size(), 3u);
  EXPECT_EQ(w[1].position, Vector3d(3, 4, 1.5));
  EXPECT_FALSE(w[0].stop);
  EXPECT_FALSE(w[1].stop);
  EXPECT_TRUE(w[2].stop);
  EXPECT_DOUBLE_EQ(w[0].tolerance_m, rules.pass_tolerance_m);
  EXPECT_DOUBLE_EQ(w[2].tolerance_m, rules.stop_tolerance_m);
}

TEST(Mission, ABadWaypointIsNamed) {
  try {
    mmh::parseWaypointList("1,2,1.2;3,x,1.5", MissionRules{});
    FAIL() << "no error";
  } catch (const MissionError& e) {
    EXPECT_NE(std::string(e.what()).find("waypoint 2 '3,x,1.5'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(mmh::parseWaypointList("", MissionRules{}), MissionError);
  EXPECT_THROW(mmh::parseWaypointList("1,2", MissionRules{}), MissionError);
}

TEST(Mission, AMissionFileSetsToleranceAndStopPerWaypoint) {
  const auto w = mmh::parseMissionYaml(
      "waypoints:\n"
      "  - position: [1, 0, 1.2]\n"
      "  - {position: [2, 0, 1.2], stop: true}\n"
      "  - {position: [3, 0, 1.2], tolerance_m: 0.5}\n",
      MissionRules{}, "m.yaml");
  ASSERT_EQ(w.size(), 3u);
  EXPECT_FALSE(w[0].stop);
  EXPECT_DOUBLE_EQ(w[0].tolerance_m, 1.0);
  EXPECT_TRUE(w[1].stop);
  EXPECT_DOUBLE_EQ(w[1].tolerance_m, 0.3);
  EXPECT_TRUE(w[2].stop);  // the last
  EXPECT_DOUBLE_EQ(w[2].tolerance_m, 0.5);
}

TEST(Mission, AMissionFileWithAnUnknownKeyOrBadValueIsRefusedByName) {
  const auto message = [](const std::string& yaml) {
    try {
      mmh::parseMissionYaml(yaml, MissionRules{}, "m.yaml");
    } catch (const MissionError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("waypoints:\n  - {position: [1, 0, 1], stopp: true}\n")
                .find("waypoint 1: unknown key 'stopp'"),
            std::string::npos);
  EXPECT_NE(message("waypoints:\n  - {position: [1, 0]}\n").find("[x, y, z]"), std::string::npos);
  EXPECT_NE(message("waypoints:\n  - {position: [1, 0, 1], tolerance_m: 0}\n").find("tolerance_m"),
            std::string::npos);
  EXPECT_NE(message("waypoint: []\n").find("unknown key 'waypoint'"), std::string::npos);
  EXPECT_NE(message("waypoints: []\n").find("no waypoint"), std::string::npos);
}

TEST(Mission, AStopIsReachedOnlyWhenSlow) {
  Waypoint pass{Vector3d(0, 0, 1), 1.0, false};
  Waypoint stop{Vector3d(0, 0, 1), 0.3, true};
  EXPECT_TRUE(mmh::waypointReached(pass, Vector3d(0.9, 0, 1), 3.0, 0.2));
  EXPECT_FALSE(mmh::waypointReached(pass, Vector3d(1.1, 0, 1), 0.0, 0.2));
  EXPECT_FALSE(mmh::waypointReached(stop, Vector3d(0.1, 0, 1), 0.5, 0.2));
  EXPECT_TRUE(mmh::waypointReached(stop, Vector3d(0.1, 0, 1), 0.1, 0.2));
}

TEST(Mission, TheSequencerMovesOnAtEachArrivalAndFinishesAtTheLast) {
  MissionSequencer m(
      {Waypoint{Vector3d(5, 0, 1), 1.0, false}, Waypoint{Vector3d(10, 0, 1), 1.0, false},
       Waypoint{Vector3d(15, 0, 1), 0.3, false}},
      0.2);
  EXPECT_TRUE(m.waypoints().back().stop);  // made a stop
  const Vector3d fast(3, 0, 0);
  EXPECT_FALSE(m.update(Vector3d(3, 0, 1), fast));
  EXPECT_EQ(m.index(), 0);
  EXPECT_TRUE(m.update(Vector3d(4.2, 0, 1), fast));  // passed at speed
  EXPECT_EQ(m.index(), 1);
  EXPECT_FALSE(m.update(Vector3d(5, 0, 1), fast));  // the first one does not count again
  EXPECT_TRUE(m.update(Vector3d(9.5, 0, 1), fast));
  EXPECT_EQ(m.index(), 2);
  EXPECT_FALSE(m.update(Vector3d(15, 0, 1), fast));  // the last: too fast
  EXPECT_FALSE(m.finished());
  EXPECT_TRUE(m.update(Vector3d(15, 0.1, 1), Vector3d(0.05, 0, 0)));
  EXPECT_TRUE(m.finished());
  EXPECT_FALSE(m.update(Vector3d(15, 0, 1), Vector3d::Zero()));
}

TEST(Geofence, AViolationNamesThePointTheAxisAndTheKeys) {
  const mmh::Geofence fence;  // +-30 m, 0.3 .. 2.7 m
  EXPECT_EQ(mmh::geofenceViolation(fence, Vector3d(0, 0, 1.5), "the goal"), "");
  const std::string why = mmh::geofenceViolation(fence, Vector3d(40, 0, 1.5), "the goal");
  EXPECT_NE(why.find("the goal [40, 0, 1.5] lies outside the geofence (x = 40 > 30)"),
            std::string::npos)
      << why;
  EXPECT_NE(why.find("geofence.min_m"), std::string::npos);
  EXPECT_NE(why.find("geofence.max_m"), std::string::npos);
  EXPECT_NE(mmh::geofenceViolation(fence, Vector3d(0, 0, 0.1), "x").find("z = 0.1 < 0.3"),
            std::string::npos);
}

TEST(Geofence, ABoxHoldsItsFacesAndNothingBeyondAnyOfThem) {
  const Vector3d lo(-1, -2, 0.3), hi(1, 2, 2.7);
  EXPECT_TRUE(mmh::insideBox(Vector3d(0, 0, 1), lo, hi));
  EXPECT_TRUE(mmh::insideBox(lo, lo, hi));
  EXPECT_TRUE(mmh::insideBox(hi, lo, hi));
  for (int axis = 0; axis < 3; ++axis) {
    Vector3d below = Vector3d(0, 0, 1), above = below;
    below[axis] = lo[axis] - 1e-9;
    above[axis] = hi[axis] + 1e-9;
    EXPECT_FALSE(mmh::insideBox(below, lo, hi)) << axis;
    EXPECT_FALSE(mmh::insideBox(above, lo, hi)) << axis;
  }
}
