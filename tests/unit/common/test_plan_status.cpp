// The one planner status of the modes and its wire codes.
#include <gtest/gtest.h>

#include <string>

#include "mmh/common/plan_status.hpp"
#include "mmh/common/plan_status_wire.hpp"
#include "mmh/plan_result_t.hpp"

namespace {

using mmh::plan_result_t;
using mmh::PlanStatus;

TEST(PlanStatus, EveryStatusHasItsWireReason) {
  const std::pair<PlanStatus, int16_t> table[] = {
      {PlanStatus::kOk, plan_result_t::REASON_NONE},
      {PlanStatus::kBadInput, plan_result_t::REASON_BAD_INPUT},
      {PlanStatus::kNoMap, plan_result_t::REASON_NO_MAP},
      {PlanStatus::kStartInObstacle, plan_result_t::REASON_START_IN_OBSTACLE},
      {PlanStatus::kTargetInObstacle, plan_result_t::REASON_TARGET_IN_OBSTACLE},
      {PlanStatus::kTargetOutOfBounds, plan_result_t::REASON_TARGET_OUT_OF_BOUNDS},
      {PlanStatus::kInfeasibleStart, plan_result_t::REASON_INFEASIBLE_START},
      {PlanStatus::kStartEqualsTarget, plan_result_t::REASON_START_EQUALS_TARGET},
      {PlanStatus::kNoPath, plan_result_t::REASON_NO_PATH},
      {PlanStatus::kCorridor, plan_result_t::REASON_CORRIDOR},
      {PlanStatus::kOptimizer, plan_result_t::REASON_OPTIMIZER},
      {PlanStatus::kVerify, plan_result_t::REASON_VERIFY},
  };
  for (const auto& [status, reason] : table) {
    EXPECT_EQ(mmh::toWireReason(status), reason) << mmh::toString(status);
    EXPECT_NE(std::string(mmh::toString(status)), "?");
  }
  EXPECT_EQ(std::string(mmh::toString(PlanStatus::kVerify)), "verification");
  EXPECT_EQ(std::string(mmh::toString(PlanStatus::kNoPath)), "no path");
}

}  // namespace
