// mmh-stack / mmh-bench: every failed flight says why (FlightRecord::failure_reason, results.json
// `reason`).
#include <gtest/gtest.h>

#include "flight_spec.hpp"
#include "stack.hpp"

using mmh::FailureEvidence;
using mmh::failureReason;

TEST(FailureReason, EveryFailureSaysWhyAndASuccessNothing) {
  FailureEvidence e;
  e.reached = true;
  EXPECT_EQ(failureReason(e), "");

  e = FailureEvidence{};
  e.collided = true;
  e.reached = true;  // reached after touching: still a collision
  e.collision_time_s = 4.25;
  e.collision_position = Eigen::Vector3d(1, -2.5, 1.2);
  EXPECT_EQ(failureReason(e), "collided at [1.00, -2.50, 1.20] after 4.25 s");

  e = FailureEvidence{};
  e.sim_time_s = 120.0;
  e.distance_to_goal_m = 12.345;
  EXPECT_EQ(failureReason(e), "timeout: not reached after 120.0 s, 12.35 m from the goal");
  e.longest_no_progress_s = 30.0;
  e.longest_no_progress_from_s = 50.0;
  EXPECT_EQ(failureReason(e),
            "stuck: no progress toward the goal for 30.0 s from 50.0 s; timeout after 120.0 s, "
            "12.35 m from the goal");
  e.unreachable_detail = "goal 1 unreachable: no progress toward it for 20 s";
  EXPECT_EQ(failureReason(e), "unreachable: goal 1 unreachable: no progress toward it for 20 s");
  e.rejected_detail = "goal 1 rejected: it lies outside the geofence";
  EXPECT_EQ(failureReason(e), "refused goal: goal 1 rejected: it lies outside the geofence");
}

TEST(FailureReason, ResultsJsonCarriesTheReason) {
  mmh::bench::FlightResult r;
  r.reason = "stuck: no progress";
  const nlohmann::json j = mmh::bench::toJson(r);
  EXPECT_EQ(j.at("reason"), "stuck: no progress");
  EXPECT_EQ(mmh::bench::fromJson(j).reason, "stuck: no progress");
  // A record written before the field existed still reads.
  nlohmann::json old = j;
  old.erase("reason");
  EXPECT_EQ(mmh::bench::fromJson(old).reason, "");
}
