// The arbiter's answer check (answer_check.hpp): the rule that the stretch in which the vehicle
// could stop lies in mapped space, on a hand-made grid.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "mmh/arbiter/answer_check.hpp"

using namespace mmh;
using namespace mmh::arbiter;

namespace {

// 10 x 4 x 3 m at 0.1 m, every cell known free; origin at (-1, -2, 0).
VoxelGrid mappedFreeGrid() {
  VoxelGrid g(0.1, Eigen::Vector3i(-10, -20, 0), Eigen::Vector3i(100, 40, 30));
  for (int z = 0; z < 30; ++z)
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 100; ++x) g.set(Eigen::Vector3i(x, y, z), Occupancy::kFree);
  return g;
}

void markUnknownSlab(VoxelGrid& g, double x_lo, double x_hi) {
  for (int z = 0; z < 30; ++z)
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 100; ++x) {
        const Eigen::Vector3i c(x, y, z);
        const double cx = g.centerOfLocal(c).x();
        if (cx >= x_lo && cx <= x_hi) g.set(c, Occupancy::kUnknown);
      }
}

// Along +x from (0, 0, 1.2): speed v0 and acceleration a, for `duration` seconds.
Trajectory straight(double v0, double a, double duration) {
  Piece p;
  p.duration = duration;
  p.coeffs.col(0) = Eigen::Vector3d(0.0, 0.0, 1.2);
  p.coeffs.col(1) = Eigen::Vector3d(v0, 0.0, 0.0);
  p.coeffs.col(2) = Eigen::Vector3d(0.5 * a, 0.0, 0.0);
  return Trajectory({p});
}

// The geofence around the grid, and a request to start at (0, 0, 1.2) with the given velocity
// and acceleration.
ArbiterParams paramsAroundTheGrid() {
  ArbiterParams p;
  p.geofence_min_m = Eigen::Vector3d(-5.0, -5.0, 0.3);
  p.geofence_max_m = Eigen::Vector3d(10.0, 5.0, 2.7);
  return p;
}

RequestedStart requestAtTheOrigin(const Eigen::Vector3d& velocity,
                                  const Eigen::Vector3d& acceleration) {
  RequestedStart requested;
  requested.start_utime = 1'000'000;
  requested.state.position = Eigen::Vector3d(0.0, 0.0, 1.2);
  requested.state.velocity = velocity;
  requested.state.acceleration = acceleration;
  return requested;
}

}  // namespace

TEST(AnswerCheck, TheKnownSpaceHorizonIsTheStoppingDistancePlusTheMargin) {
  ArbiterParams p;
  p.max_acc_mps2 = 2.0;
  p.known_space_margin_m = 0.3;
  EXPECT_DOUBLE_EQ(knownSpaceHorizonM(0.0, p), 0.3);
  EXPECT_DOUBLE_EQ(knownSpaceHorizonM(3.0, p), 9.0 / 4.0 + 0.3);
}

TEST(AnswerCheck, UnmappedSpaceWithinTheStopIsFoundAndBeyondItIsNot) {
  VoxelGrid g = mappedFreeGrid();
  const Trajectory from_rest = straight(0.0, 1.0, 3.0);  // 4.5 m
  EXPECT_FALSE(firstUnknownWithin(from_rest, g, 0.3, 0.01));
  markUnknownSlab(g, 0.2, 0.4);  // right ahead of the start
  UnmappedCell where;
  const auto at = firstUnknownWithin(from_rest, g, 0.3, 0.01, {}, &where);
  ASSERT_TRUE(at);
  EXPECT_NEAR(*at, std::sqrt(2.0 * 0.2), 0.02);  // x = t^2 / 2 reaches the slab at 0.2 m
  // The slab's first cell on the path, centred at x = 0.25 m.
  EXPECT_NEAR(where.center.x(), 0.25, 1e-9);
  EXPECT_NEAR(where.center.y(), 0.05, 0.051);
  EXPECT_FALSE(where.beside_path);
  // Farther than the horizon: space the sensor will see on the way.
  VoxelGrid far = mappedFreeGrid();
  markUnknownSlab(far, 2.0, 2.2);
  EXPECT_FALSE(firstUnknownWithin(from_rest, far, 0.3, 0.01));
  // At 3 m/s the stop needs 2.25 m: the same slab is within it.
  EXPECT_TRUE(firstUnknownWithin(straight(3.0, 0.0, 2.0), far, 2.55, 0.01));
  // The start's own cell does not count (the vehicle is there, seen or not).
  VoxelGrid own = mappedFreeGrid();
  own.set(own.localIndexOf(Eigen::Vector3d(0.0, 0.0, 1.2)), Occupancy::kUnknown);
  EXPECT_FALSE(firstUnknownWithin(from_rest, own, 0.3, 0.01));
}

// A trunk seen from one side only, as a forward camera that passed it leaves it: occupied cells
// on its north face (y = 0.4-0.5 m) and unknown cells where its east face would be, 0.1-0.4 m
// beside a path that creeps along +x at y = 0 (cells at x = 1.0-1.1 m, or centred at x).
VoxelGrid trunkSeenFromOneSide(double x = 1.05) {
  VoxelGrid g = mappedFreeGrid();
  for (int z = 0; z < 30; ++z) {
    const double cz = (z + 0.5) * 0.1;
    for (double y : {0.15, 0.25, 0.35}) g.set(g.localIndexOf({x, y, cz}), Occupancy::kUnknown);
    g.set(g.localIndexOf({x, 0.45, cz}), Occupancy::kOccupied);
  }
  return g;
}

TEST(AnswerCheck, AnUnseenSideOfAMappedObstacleBesideThePathCounts) {
  const VoxelGrid g = trunkSeenFromOneSide();
  const Trajectory creep = straight(0.5, 0.0, 4.0);  // 2 m along +x at 0.5 m/s
  // The centre line lies in seen space: the centre-line rule alone lets it pass.
  EXPECT_FALSE(firstUnknownWithin(creep, g, 2.0, 0.01));
  EXPECT_FALSE(firstUnknownWithin(creep, g, 2.0, 0.01, {0.15, 0.0, 2.0}));
  // A 0.15 m airframe touches the unknown cell at y = 0.1-0.2 m, 0.3 m from the occupied one.
  UnmappedCell where;
  const auto at = firstUnknownWithin(creep, g, 2.0, 0.01, {0.15, 0.3, 2.0}, &where);
  ASSERT_TRUE(at);
  // It reaches the cell's near face (x = 1.0) when the centre is at x = 1.0 - sqrt(0.15^2 -
  // 0.1^2) = 0.888 m.
  EXPECT_NEAR(*at, (1.0 - std::sqrt(0.15 * 0.15 - 0.1 * 0.1)) / 0.5, 0.03);
  EXPECT_TRUE(where.beside_path);
  EXPECT_NEAR(where.center.x(), 1.05, 1e-9);
  EXPECT_NEAR(where.center.y(), 0.15, 1e-9);
  // Beyond the horizon it does not count yet.
  EXPECT_FALSE(firstUnknownWithin(creep, g, 0.8, 0.01, {0.15, 0.3, 2.0}));
  // In plain sight of the start, it counts beyond the reach beside the path too: a side the
  // sensor could have seen from here but never looked at.
  EXPECT_TRUE(firstUnknownWithin(creep, g, 2.0, 0.01, {0.15, 0.3, 0.1}));
}

TEST(AnswerCheck, AnObstaclesShadowBesideThePathCountsOnlyNearTheStart) {
  // 1 m along +x, then 1 m along +y (1 m/s each). Beside the second leg, at x = 1.1-1.2 m,
  // y = 0.5-0.6 m, an unknown cell 0.2 m from a mapped obstacle's face (x = 1.3-1.4 m).
  mmh::Piece along_x, along_y;
  along_x.duration = along_y.duration = 1.0;
  along_x.coeffs.col(0) = Eigen::Vector3d(0.0, 0.0, 1.25);
  along_x.coeffs.col(1) = Eigen::Vector3d(1.0, 0.0, 0.0);
  along_y.coeffs.col(0) = Eigen::Vector3d(1.0, 0.0, 1.25);
  along_y.coeffs.col(1) = Eigen::Vector3d(0.0, 1.0, 0.0);
  const Trajectory corner({along_x, along_y});
  VoxelGrid g = mappedFreeGrid();
  for (int z = 0; z < 30; ++z) {
    const double cz = (z + 0.5) * 0.1;
    g.set(g.localIndexOf({1.15, 0.55, cz}), Occupancy::kUnknown);
    g.set(g.localIndexOf({1.35, 0.55, cz}), Occupancy::kOccupied);
  }
  // In plain sight of the start: counted, about 1.45 m along the path.
  const auto at = firstUnknownWithin(corner, g, 3.0, 0.01, {0.15, 0.3, 0.5});
  ASSERT_TRUE(at);
  EXPECT_NEAR(*at, 1.0 + 0.5 - std::sqrt(0.15 * 0.15 - 0.1 * 0.1), 0.03);
  // A mapped obstacle between the start and that cell (at x = 0.5-0.6 m, y = 0.2-0.3 m, clear
  // of the path): the cell lies in its shadow, which the sensor sees on the way. It counts
  // only within the reach.
  for (int z = 0; z < 30; ++z)
    g.set(g.localIndexOf({0.55, 0.25, (z + 0.5) * 0.1}), Occupancy::kOccupied);
  EXPECT_FALSE(firstUnknownWithin(corner, g, 3.0, 0.01, {0.15, 0.3, 0.5}));
  EXPECT_TRUE(firstUnknownWithin(corner, g, 3.0, 0.01, {0.15, 0.3, 1.5}));
}

TEST(AnswerCheck, UnknownCellsBesideThePathAwayFromObstaclesDoNotCount) {
  // The same unknown cells with nothing mapped near them: the flank of the vehicle's own
  // body, which a forward camera never sees, must not hold a vehicle whose plan turns.
  VoxelGrid g = mappedFreeGrid();
  for (int z = 0; z < 30; ++z)
    for (double y : {0.15, 0.25, 0.35})
      g.set(g.localIndexOf({1.05, y, (z + 0.5) * 0.1}), Occupancy::kUnknown);
  const Trajectory creep = straight(0.5, 0.0, 4.0);
  EXPECT_FALSE(firstUnknownWithin(creep, g, 2.0, 0.01, {0.15, 0.3, 2.0}));
  // An obstacle farther than hidden_face_m from them: its unseen side is not there either.
  VoxelGrid far = trunkSeenFromOneSide();
  EXPECT_FALSE(firstUnknownWithin(creep, far, 2.0, 0.01, {0.15, 0.15, 2.0}));
  // Cells the airframe touches where it is now do not count, even next to an obstacle.
  VoxelGrid own = trunkSeenFromOneSide();
  Piece p;
  p.duration = 2.0;
  p.coeffs.col(0) = Eigen::Vector3d(1.0, 0.0, 1.2);
  p.coeffs.col(1) = Eigen::Vector3d(-0.5, 0.0, 0.0);  // backing away along -x
  EXPECT_FALSE(firstUnknownWithin(Trajectory({p}), own, 1.0, 0.01, {0.15, 0.3, 2.0}));
}

TEST(AnswerCheck, AnAnswerAlongAnUnseenSideOfAnObstacleIsRefused) {
  // Vehicle radius 0.15 m; unknown cells within 0.3 m of an occupied one and 0.5 m of path count.
  const ArbiterParams p = paramsAroundTheGrid();
  const RequestedStart requested =
      requestAtTheOrigin(Eigen::Vector3d(0.5, 0.0, 0.0), Eigen::Vector3d::Zero());
  const Trajectory creep = straight(0.5, 0.0, 4.0);
  std::string why;
  VoxelGrid seen = mappedFreeGrid();
  EXPECT_TRUE(checkAnswer(creep, requested.start_utime, requested, &seen, p, 1.5, &why)) << why;
  // The airframe touches the unseen face 0.29 m from the start.
  VoxelGrid g = trunkSeenFromOneSide(0.45);
  EXPECT_FALSE(checkAnswer(creep, requested.start_utime, requested, &g, p, 1.5, &why));
  EXPECT_NE(why.find("enters unmapped space"), std::string::npos) << why;
  ArbiterParams centre_line_only = p;
  centre_line_only.hidden_face_m = 0.0;
  EXPECT_TRUE(checkAnswer(creep, requested.start_utime, requested, &g, centre_line_only, 1.5, &why))
      << why;
  // 1 m on, beyond the answer's reach (1.5 s of path, its stop and the margin).
  VoxelGrid farther = trunkSeenFromOneSide(1.45);
  EXPECT_TRUE(checkAnswer(creep, requested.start_utime, requested, &farther, p, 1.5, &why)) << why;
}

TEST(AnswerCheck, AStopBesideAnUnseenSideOfAnObstacleTouchesIt) {
  ArbiterParams p = paramsAroundTheGrid();  // radius 0.15 m, hidden face 0.3 m
  const VoxelGrid g = trunkSeenFromOneSide();
  // Braking from 1 m/s along +x at y = 0: 0.25 m, short of the face at x = 1.0 m.
  EXPECT_FALSE(touchesHiddenFace(straight(1.0, -2.0, 0.5), g, p));
  // The same stop from x = 0.7 m would brake beside the face, far from the start or not.
  Piece from_there;
  from_there.duration = 0.5;
  from_there.coeffs.col(0) = Eigen::Vector3d(0.7, 0.0, 1.2);
  from_there.coeffs.col(1) = Eigen::Vector3d(1.0, 0.0, 0.0);
  from_there.coeffs.col(2) = Eigen::Vector3d(-1.0, 0.0, 0.0);
  EXPECT_TRUE(touchesHiddenFace(Trajectory({from_there}), g, p));
  p.hidden_face_m = 0.0;
  EXPECT_FALSE(touchesHiddenFace(Trajectory({from_there}), g, p));
}

TEST(AnswerCheck, AnAnswerWhoseStopWouldEndInUnmappedSpaceIsRefused) {
  ArbiterParams p = paramsAroundTheGrid();
  const RequestedStart requested =
      requestAtTheOrigin(Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 0.0, 0.0));
  const Trajectory answer = straight(0.0, 1.0, 2.0);
  VoxelGrid g = mappedFreeGrid();
  std::string why;
  EXPECT_TRUE(checkAnswer(answer, requested.start_utime, requested, &g, p, 0.0, &why)) << why;
  markUnknownSlab(g, 0.2, 0.4);
  EXPECT_FALSE(checkAnswer(answer, requested.start_utime, requested, &g, p, 0.0, &why));
  EXPECT_NE(why.find("enters unmapped space"), std::string::npos) << why;
  EXPECT_NE(why.find("at (0.25, "), std::string::npos) << why;  // where: the slab's first cell
  EXPECT_NE(why.find("on its path"), std::string::npos) << why;
  p.known_space_margin_m = 0.1;  // a stop from rest that ends before the slab
  EXPECT_TRUE(checkAnswer(answer, requested.start_utime, requested, &g, p, 0.0, &why)) << why;
}

TEST(AnswerCheck, AnAnswerSpeedingUpFromRestIsCheckedFromWhereTheNextMapFindsIt) {
  ArbiterParams p = paramsAroundTheGrid();
  p.max_acc_mps2 = 2.0;
  p.known_space_margin_m = 0.3;
  const RequestedStart requested =
      requestAtTheOrigin(Eigen::Vector3d::Zero(), Eigen::Vector3d(2.0, 0.0, 0.0));
  const Trajectory answer = straight(0.0, 2.0, 1.0);
  // From rest the stop is 0 m: only the margin (0.3 m) must be mapped at the start. After 0.5 s
  // the vehicle is at x = 0.25 m at 1 m/s and needs 0.25 m to stop, plus the margin: x = 0.8 m.
  VoxelGrid g = mappedFreeGrid();
  markUnknownSlab(g, 0.65, 0.75);
  std::string why;
  EXPECT_TRUE(checkAnswer(answer, requested.start_utime, requested, &g, p, 0.0, &why)) << why;
  EXPECT_FALSE(checkAnswer(answer, requested.start_utime, requested, &g, p, 0.5, &why));
  EXPECT_NE(why.find("enters unmapped space"), std::string::npos) << why;
  // The same answer with the slab beyond that reach.
  VoxelGrid farther = mappedFreeGrid();
  markUnknownSlab(farther, 0.95, 1.05);
  EXPECT_TRUE(checkAnswer(answer, requested.start_utime, requested, &farther, p, 0.5, &why)) << why;
}

TEST(AnswerCheck, ARefusedAnswerSaysWhereItMeetsTheMap) {
  const ArbiterParams p = paramsAroundTheGrid();
  const RequestedStart requested =
      requestAtTheOrigin(Eigen::Vector3d(2.0, 0.0, 0.0), Eigen::Vector3d::Zero());
  const Trajectory answer = straight(2.0, 0.0, 2.0);  // 4 m along +x
  VoxelGrid g = mappedFreeGrid();
  std::string why;
  ASSERT_TRUE(checkAnswer(answer, requested.start_utime, requested, &g, p, 0.0, &why)) << why;
  // One occupied cell beside the way at x = 3 m: the 0.25 m margin reaches the way.
  g.setInflationRadius(0.25);
  g.set(g.localIndexOf(Eigen::Vector3d(3.05, 0.15, 1.25)), Occupancy::kOccupied);
  EXPECT_FALSE(checkAnswer(answer, requested.start_utime, requested, &g, p, 0.0, &why));
  // Where the way enters the margin: about 1.4 s (x = 2.8 m), named with the place.
  EXPECT_EQ(why.rfind("collides with the arbiter's map ", 0), 0u) << why;
  double at_s = 0.0, x = 0.0, y = 0.0, z = 0.0;
  ASSERT_EQ(std::sscanf(why.c_str(),
                        "collides with the arbiter's map %lf s from its start, at "
                        "(%lf, %lf, %lf)",
                        &at_s, &x, &y, &z),
            4)
      << why;
  EXPECT_NEAR(at_s, 1.4, 0.06);
  EXPECT_NEAR(x, 2.0 * at_s, 0.011);
  EXPECT_NEAR(y, 0.0, 1e-9);
  EXPECT_NEAR(z, 1.2, 1e-9);
  // A geofence 2 m ahead (0.05 m tolerance): named the same way.
  ArbiterParams fenced = p;
  fenced.geofence_max_m.x() = 2.0;
  EXPECT_FALSE(checkAnswer(answer, requested.start_utime, requested, nullptr, fenced, 0.0, &why));
  ASSERT_EQ(std::sscanf(why.c_str(), "leaves the geofence %lf s from its start, at (%lf, %lf, %lf)",
                        &at_s, &x, &y, &z),
            4)
      << why;
  EXPECT_GT(x, 2.05);  // the first time-step sample past the fence and its tolerance
  EXPECT_LE(x, 2.05 + 2.0 * p.check_step_s + 1e-9);
  EXPECT_NEAR(at_s, x / 2.0, 1e-6);
}

TEST(AnswerCheck, TheCommittedTrajectorysReachIsTheLeadThenTheStopFromTheSpeedThere) {
  ArbiterParams p;
  p.max_acc_mps2 = 2.0;
  p.known_space_margin_m = 0.3;
  p.check_step_s = 0.01;
  // 3 m/s along +x for 4 s; 1 s flown (x = 3 m). The reach: 0.5 s of lead (1.5 m), then the
  // stop from 3 m/s (2.25 m) and the margin: up to x = 7.05 m.
  const Trajectory cruise = straight(3.0, 0.0, 4.0);
  VoxelGrid g = mappedFreeGrid();
  EXPECT_FALSE(firstUnknownWithinReach(cruise, 1.0, 0.5, g, p));
  markUnknownSlab(g, 6.9, 7.0);
  const auto at = firstUnknownWithinReach(cruise, 1.0, 0.5, g, p);
  ASSERT_TRUE(at);
  EXPECT_NEAR(*at, 6.9 / 3.0, 0.02);  // time on the trajectory, from its start
  // A shorter lead no longer reaches the slab; neither does the same lead from farther back.
  EXPECT_FALSE(firstUnknownWithinReach(cruise, 1.0, 0.4, g, p));
  EXPECT_FALSE(firstUnknownWithinReach(cruise, 0.9, 0.5, g, p));
  // Unmapped space already passed is not ahead.
  EXPECT_FALSE(firstUnknownWithinReach(cruise, 2.5, 0.5, g, p));
  // Flown to its end: nothing left to reach.
  EXPECT_FALSE(firstUnknownWithinReach(cruise, 4.0, 0.5, g, p));
}
