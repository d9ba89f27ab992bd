#include <gtest/gtest.h>

#include <cmath>

#include "mmh/arbiter/stopping_trajectory.hpp"
#include "mmh/common/minco.hpp"

TEST(StoppingTrajectory, BrakesToRestWithinTheLimitsWithoutAJump) {
  for (double speed : {0.5, 1.5, 3.0}) {
    mmh::KinematicState s;
    s.position = Eigen::Vector3d(1, 2, 1.2);
    s.velocity = Eigen::Vector3d(speed * 0.6, speed * 0.8, 0.0);
    s.acceleration = Eigen::Vector3d(0.3, -0.2, 0.0);
    mmh::Trajectory t = mmh::arbiter::makeStoppingTrajectory(s, 2.0, 3.0);
    EXPECT_LT((t.position(0) - s.position).norm(), 1e-9);
    EXPECT_LT((t.velocity(0) - s.velocity).norm(), 1e-9);
    EXPECT_LT((t.acceleration(0) - s.acceleration).norm(), 1e-9);
    EXPECT_LT(t.velocity(t.duration()).norm(), 1e-6);
    EXPECT_LT(t.acceleration(t.duration()).norm(), 1e-6);
    EXPECT_LE(t.maxAcceleration(), 2.0 + 1e-9);
    // A start acceleration can raise the speed a little before braking takes over.
    EXPECT_LE(t.maxSpeed(), std::max(3.0, speed) + 0.01);
    // Stops along the direction of motion, not much farther than a bang-bang stop would.
    const double bang_bang = speed * speed / (2 * 2.0);
    const Eigen::Vector3d travel = t.position(t.duration()) - s.position;
    EXPECT_GT(travel.dot(s.velocity.normalized()), 0.0);
    EXPECT_LT(travel.norm(), 2.5 * bang_bang + 0.2);
  }
}

TEST(StoppingTrajectory, AtRestItHolds) {
  mmh::KinematicState s;
  s.position = Eigen::Vector3d(1, 2, 3);
  mmh::Trajectory t = mmh::arbiter::makeStoppingTrajectory(s, 2.0, 3.0);
  EXPECT_TRUE(t.position(0.5).isApprox(s.position));
  EXPECT_LT(t.maxSpeed(), 1e-12);
}

// A start that already brakes at (or, after a tolerated emergency answer, above) a_max: the stop
// keeps at most that acceleration and takes about as long as braking at a_max, not a minute.
TEST(StoppingTrajectory, StartAtOrAboveTheAccelerationLimitStopsPromptly) {
  for (const Eigen::Vector3d& acc :
       {Eigen::Vector3d(-2.0, 0.0, 0.0), Eigen::Vector3d(-2.0, 0.6, 0.0),
        Eigen::Vector3d(-1.2, 1.7, 0.0), Eigen::Vector3d(0.5, 2.0, 0.2)}) {
    mmh::KinematicState s;
    s.position = Eigen::Vector3d(0, 0, 1.2);
    s.velocity = Eigen::Vector3d(3.0, 0.0, 0.0);
    s.acceleration = acc;
    const mmh::Trajectory t = mmh::arbiter::makeStoppingTrajectory(s, 2.0, 3.0);
    EXPECT_LT((t.acceleration(0) - acc).norm(), 1e-9);
    EXPECT_LT(t.velocity(t.duration()).norm(), 1e-6);
    EXPECT_LE(t.maxAcceleration(), std::max(2.0, acc.norm()) * 1.01) << acc.transpose();
    EXPECT_LT(t.duration(), 4.0 * 3.0 / 2.0 + 2.0) << acc.transpose();
    EXPECT_LT((t.position(t.duration()) - s.position).norm(), 2.5 * 9.0 / 4.0 + 0.5);
  }
}

TEST(StoppingTrajectory, RestoppingAStopInProgressKeepsBraking) {
  mmh::KinematicState s;
  s.position = Eigen::Vector3d(0, 0, 1.2);
  s.velocity = Eigen::Vector3d(3.0, 0.0, 0.0);
  const mmh::Trajectory first = mmh::arbiter::makeStoppingTrajectory(s, 2.0, 3.0);
  const Eigen::Vector3d end = first.position(first.duration());
  for (double t0 : {0.2, 0.5, 0.9}) {
    const mmh::Trajectory again = mmh::arbiter::makeStoppingTrajectory(first, t0, 2.0, 3.0);
    const mmh::KinematicState at = first.state(t0);
    EXPECT_LT((again.acceleration(0) - at.acceleration).norm(), 1e-9);
    EXPECT_LE(again.maxAcceleration(), std::max(2.0, at.acceleration.norm()) * 1.01);
    EXPECT_LT(again.duration(), first.duration() - t0 + 3.0);
    // It does not carry the vehicle much past where the first stop ended.
    EXPECT_LT((again.position(again.duration()) - end).norm(), 1.0) << t0;
  }
}

namespace {

// 16 x 8 x 3 m of free space at 0.1 m (x from -2, y from -4), with an optional vertical pillar.
mmh::VoxelGrid gridWithPillar(double x, double y, double radius) {
  mmh::VoxelGrid g(0.1, Eigen::Vector3i(-20, -40, 0), Eigen::Vector3i(160, 80, 30));
  g.setInflationRadius(0.25);
  for (int64_t i = 0; i < g.numCells(); ++i) {
    const Eigen::Vector3d c = g.centerOfLocal(g.localFromLinear(i));
    g.setLinear(i, std::hypot(c.x() - x, c.y() - y) <= radius ? mmh::Occupancy::kOccupied
                                                              : mmh::Occupancy::kFree);
  }
  return g;
}

}  // namespace

// Stopped for danger ahead on a path that bends into a pillar: braking along it (which keeps an
// avoidance under way) would end 13 cm from its occupied cells, so the straight stop is taken;
// with the way clear, the stop along the path.
TEST(StoppingTrajectory, ChoosesTheStopThatKeepsClearOfTheObstacle) {
  mmh::MincoJerk m;
  Eigen::Matrix3d head, tail;
  head << Eigen::Vector3d(0, 0, 1.2), Eigen::Vector3d(2, 0, 0), Eigen::Vector3d::Zero();
  tail << Eigen::Vector3d(2.0, 2.5, 1.2), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero();
  m.setConditions(head, tail, 1);
  m.setParameters(Eigen::Matrix3Xd(3, 0), Eigen::VectorXd::Constant(1, 3.0));
  const mmh::Trajectory path = m.trajectory();
  const mmh::VoxelGrid clear = gridWithPillar(1.75, 0.85, 0.0);
  const mmh::VoxelGrid pillar = gridWithPillar(1.75, 0.85, 0.3);
  const double clearance = 0.25;
  const mmh::Trajectory along = mmh::arbiter::makeStoppingTrajectory(path, 0.0, 2.0, 3.0);
  ASSERT_LT(mmh::arbiter::minOccupiedDistance(pillar, along, 1.0), 0.15);

  const mmh::Trajectory chosen =
      mmh::arbiter::chooseStoppingTrajectory(&pillar, path, 0.0, 2.0, 3.0, clearance);
  EXPECT_GE(mmh::arbiter::minOccupiedDistance(pillar, chosen, 1.0), clearance);
  EXPECT_LT((chosen.position(0) - path.position(0)).norm(), 1e-9);
  EXPECT_LT((chosen.velocity(0) - path.velocity(0)).norm(), 1e-9);
  EXPECT_LT(chosen.velocity(chosen.duration()).norm(), 1e-6);
  EXPECT_LE(chosen.maxAcceleration(), 2.0 + 1e-6);

  const mmh::Trajectory kept =
      mmh::arbiter::chooseStoppingTrajectory(&clear, path, 0.0, 2.0, 3.0, clearance);
  EXPECT_LT((kept.position(kept.duration()) - along.position(along.duration())).norm(), 1e-9);
}
