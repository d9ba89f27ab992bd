// The shared trajectory verifier: each failure reason on its own.
#include <gtest/gtest.h>

#include "mmh/common/trajectory_verifier.hpp"

namespace {

using Eigen::Vector3d;
using Eigen::Vector3i;
using mmh::VerifierOptions;
using mmh::VerifyCheck;

// x(t) = t^2 - t^3 / 3 on [0, 2] at y = z = 1.05: from rest at x = 0 to rest at x = 4/3, max
// speed 1 (t = 1), max acceleration 2 (the ends).
mmh::Trajectory line() {
  mmh::Piece p;
  p.duration = 2.0;
  p.coeffs(0, 2) = 1.0;
  p.coeffs(0, 3) = -1.0 / 3.0;
  p.coeffs(1, 0) = 1.05;
  p.coeffs(2, 0) = 1.05;
  return mmh::Trajectory({p});
}

VerifierOptions allChecks(const mmh::VoxelGrid* grid) {
  VerifierOptions o;
  o.check_start = true;
  o.start.position = Vector3d(0, 1.05, 1.05);
  o.start.acceleration = Vector3d(2, 0, 0);
  o.check_end = true;
  o.target = Vector3d(4.0 / 3.0, 1.05, 1.05);
  o.rest_acceleration_tol_mps2 = 2.1;  // a(2) = -2: "at rest" is about the velocity here
  o.check_limits = true;
  o.max_vel_mps = 1.0;
  o.max_acc_mps2 = 2.0;
  o.limit_relative_tol = 1e-6;
  o.check_geofence = true;
  o.geofence_min = Vector3d(-1, 0, 0);
  o.geofence_max = Vector3d(3, 3, 3);
  o.grid = grid;
  return o;
}

class Verifier : public ::testing::Test {
 protected:
  Verifier() : grid_(0.1, Vector3i(-10, 0, 0), Vector3i(50, 30, 30)) {}
  mmh::VoxelGrid grid_;
};

TEST_F(Verifier, AGoodTrajectoryPasses) {
  for (auto sampling :
       {VerifierOptions::Sampling::kPerPiece, VerifierOptions::Sampling::kTimeSteps}) {
    VerifierOptions o = allChecks(&grid_);
    o.sampling = sampling;
    const mmh::VerifyResult r = mmh::verifyTrajectory(line(), o);
    EXPECT_TRUE(r.ok) << r.why;
    EXPECT_NEAR(r.max_speed, 1.0, 1e-9);
    EXPECT_NEAR(r.max_acc, 2.0, 1e-9);
  }
}

TEST_F(Verifier, EachFailureReason) {
  auto failed = [&](const mmh::Trajectory& t, const VerifierOptions& o) {
    return mmh::verifyTrajectory(t, o).failed;
  };
  EXPECT_EQ(failed(mmh::Trajectory(), allChecks(&grid_)), VerifyCheck::kNotFinite);
  VerifierOptions o = allChecks(&grid_);
  o.start.velocity = Vector3d(0.1, 0, 0);
  EXPECT_EQ(failed(line(), o), VerifyCheck::kStartState);
  o = allChecks(&grid_);
  o.target.x() += 0.1;
  EXPECT_EQ(failed(line(), o), VerifyCheck::kEndPosition);
  o = allChecks(&grid_);
  o.rest_acceleration_tol_mps2 = 1e-3;
  EXPECT_EQ(failed(line(), o), VerifyCheck::kEndNotAtRest);
  o = allChecks(&grid_);
  o.max_vel_mps = 0.99;
  EXPECT_EQ(failed(line(), o), VerifyCheck::kSpeed);
  o.limit_relative_tol = 0.02;  // 0.99 * 1.02 > 1
  EXPECT_EQ(failed(line(), o), VerifyCheck::kNone);
  o = allChecks(&grid_);
  o.max_acc_mps2 = 1.9;
  EXPECT_EQ(failed(line(), o), VerifyCheck::kAcceleration);
  o.limit_absolute_tol = 0.2;
  EXPECT_EQ(failed(line(), o), VerifyCheck::kNone);
  o = allChecks(&grid_);
  o.geofence_max.x() = 1.0;
  EXPECT_EQ(failed(line(), o), VerifyCheck::kGeofence);
  o.geofence_tol_m = 0.5;
  EXPECT_EQ(failed(line(), o), VerifyCheck::kNone);
  o = allChecks(&grid_);
  o.sample_check = [](int, double t, const Vector3d&, std::string* why) {
    *why = "late";
    return t < 1.5;
  };
  const mmh::VerifyResult late = mmh::verifyTrajectory(line(), o);
  EXPECT_EQ(late.failed, VerifyCheck::kSample);
  EXPECT_EQ(late.why, "late");
  EXPECT_GE(late.at_time, 1.5);
}

TEST_F(Verifier, CollisionsAndTheEscape) {
  // An occupied cell on the way at x = 1.0 (cell 20 from the window origin -10 at 0.1 m).
  mmh::VoxelGrid blocked = grid_;
  blocked.set(Vector3i(20, 10, 10), mmh::Occupancy::kOccupied);
  for (auto sampling :
       {VerifierOptions::Sampling::kPerPiece, VerifierOptions::Sampling::kTimeSteps}) {
    VerifierOptions o = allChecks(&blocked);
    o.sampling = sampling;
    const mmh::VerifyResult r = mmh::verifyTrajectory(line(), o);
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(r.collision()) << mmh::toString(r.failed);
  }
  // Inflated only: occupied beside the path (y = 1.25), margin 0.25 m.
  mmh::VoxelGrid margin = grid_;
  margin.setInflationRadius(0.25);
  margin.set(Vector3i(20, 12, 10), mmh::Occupancy::kOccupied);
  VerifierOptions o = allChecks(&margin);
  EXPECT_EQ(mmh::verifyTrajectory(line(), o).failed, VerifyCheck::kInflated);
  o.check_inflated = false;
  EXPECT_EQ(mmh::verifyTrajectory(line(), o).failed, VerifyCheck::kNone);
  // A start inside the margin of an obstacle just behind it leaves outwards: allowed; with a
  // too large minimum distance it "goes deeper"; with a tiny escape radius it stays too far.
  mmh::VoxelGrid behind = grid_;
  behind.setInflationRadius(0.25);
  behind.set(Vector3i(8, 10, 10), mmh::Occupancy::kOccupied);  // x = -0.15
  o = allChecks(&behind);
  o.escape_min_distance_m = mmh::escapeMinDistance(behind, o.start.position, 0.25);
  EXPECT_TRUE(mmh::verifyTrajectory(line(), o).ok) << mmh::verifyTrajectory(line(), o).why;
  o.escape_radius_m = 1e-3;
  EXPECT_EQ(mmh::verifyTrajectory(line(), o).failed, VerifyCheck::kEscapeTooFar);
  o = allChecks(&behind);
  o.escape_min_distance_m = 1.0;
  EXPECT_EQ(mmh::verifyTrajectory(line(), o).failed, VerifyCheck::kEscapeDeeper);
  o.escape_from_first_sample = false;  // start blocked: still escaping
  EXPECT_EQ(mmh::verifyTrajectory(line(), o).failed, VerifyCheck::kEscapeDeeper);
}

TEST_F(Verifier, NearTheStartTheEscapeMayTouchTheMarginAgainKeepingItsDistance) {
  // Start 0.15 m in front of an obstacle (margin 0.25 m); the way out leaves that margin near
  // x = 0.1 and crosses cells whose centres lie 0.2 m from another one beside it (x = 0.35,
  // y = 1.25) while the path keeps more than the start's distance to every occupied cell.
  mmh::VoxelGrid grid = grid_;
  grid.setInflationRadius(0.25);
  grid.set(Vector3i(8, 10, 10), mmh::Occupancy::kOccupied);   // x = -0.15
  grid.set(Vector3i(13, 12, 10), mmh::Occupancy::kOccupied);  // (0.35, 1.25)
  VerifierOptions o = allChecks(&grid);
  o.sampling = VerifierOptions::Sampling::kTimeSteps;
  o.escape_min_distance_m = mmh::escapeMinDistance(grid, o.start.position, 0.25);
  o.escape_radius_m = 0.5;
  const mmh::VerifyResult within = mmh::verifyTrajectory(line(), o);
  EXPECT_TRUE(within.ok) << within.why;
  // Beyond the escape radius the same cells are a collision.
  o.escape_radius_m = 0.1;
  EXPECT_EQ(mmh::verifyTrajectory(line(), o).failed, VerifyCheck::kInflated);
  // And near the start, nearer than the start was is still refused.
  o.escape_radius_m = 0.5;
  o.escape_min_distance_m = 0.22;
  EXPECT_EQ(mmh::verifyTrajectory(line(), o).failed, VerifyCheck::kEscapeDeeper);
}

TEST_F(Verifier, MarginCellsTheStartStateFixesKeepTheEscapeDistance) {
  // Occupied at (0.35, 1.25): the path (y = 1.05) crosses margin cells for x in [0.2, 0.5]
  // (t in about [0.48, 0.8] s), never nearer to that cell's centre than 0.2 m.
  mmh::VoxelGrid beside = grid_;
  beside.setInflationRadius(0.25);
  beside.set(Vector3i(13, 12, 10), mmh::Occupancy::kOccupied);
  VerifierOptions o = allChecks(&beside);
  EXPECT_EQ(mmh::verifyTrajectory(line(), o).failed, VerifyCheck::kInflated);
  o.escape_min_distance_m = 0.2;
  o.forced_until_s = 1.0;
  EXPECT_TRUE(mmh::verifyTrajectory(line(), o).ok) << mmh::verifyTrajectory(line(), o).why;
  o.forced_until_s = 0.6;  // lets go in the middle of the crossing
  EXPECT_EQ(mmh::verifyTrajectory(line(), o).failed, VerifyCheck::kInflated);
  o.forced_until_s = 1.0;
  o.escape_min_distance_m = 0.25;  // the crossing comes nearer than that
  EXPECT_EQ(mmh::verifyTrajectory(line(), o).failed, VerifyCheck::kInflated);
}

}  // namespace
