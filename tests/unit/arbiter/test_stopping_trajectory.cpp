#include <gtest/gtest.h>

#include "mmh/arbiter/stopping_trajectory.hpp"

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
