// The take-over queue of committed trajectories shared by the simulated vehicle and mmh-setpoint.
#include <gtest/gtest.h>

#include "mmh/common/trajectory_schedule.hpp"

using mmh::ScheduledTrajectory;
using mmh::TrajectorySchedule;

TEST(TrajectorySchedule, HandsTrajectoriesOverInStartOrderOnlyWhenDue) {
  TrajectorySchedule s;
  s.commit(nullptr, 100, 1);
  s.commit(nullptr, 200, 2);
  EXPECT_FALSE(s.popDue(99).has_value());
  const auto first = s.popDue(150);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->id, 1);
  EXPECT_FALSE(s.popDue(199).has_value());
  EXPECT_EQ(s.popDue(200)->id, 2);
  EXPECT_FALSE(s.hasQueued());
}

TEST(TrajectorySchedule, ALaterCommitReplacesQueuedOnesThatStartAtOrAfterIt) {
  TrajectorySchedule s;
  s.commit(nullptr, 100, 1);
  s.commit(nullptr, 300, 2);
  s.commit(nullptr, 300, 3);  // same start: replaces 2
  s.commit(nullptr, 200, 4);  // earlier start: replaces 3
  EXPECT_EQ(s.popDue(1000)->id, 1);
  EXPECT_EQ(s.popDue(1000)->id, 4);
  EXPECT_FALSE(s.popDue(1000).has_value());
}
