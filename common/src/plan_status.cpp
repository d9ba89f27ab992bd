#include "mmh/common/plan_status.hpp"

#include "mmh/common/plan_status_wire.hpp"
#include "mmh/plan_result_t.hpp"

namespace mmh {

const char* toString(PlanStatus status) {
  switch (status) {
    case PlanStatus::kOk:
      return "ok";
    case PlanStatus::kBadInput:
      return "bad input";
    case PlanStatus::kNoMap:
      return "no map";
    case PlanStatus::kStartInObstacle:
      return "start in obstacle";
    case PlanStatus::kTargetInObstacle:
      return "target in obstacle";
    case PlanStatus::kTargetOutOfBounds:
      return "target out of bounds";
    case PlanStatus::kInfeasibleStart:
      return "infeasible start";
    case PlanStatus::kStartEqualsTarget:
      return "start equals target";
    case PlanStatus::kNoPath:
      return "no path";
    case PlanStatus::kCorridor:
      return "corridor";
    case PlanStatus::kOptimizer:
      return "optimizer";
    case PlanStatus::kVerify:
      return "verification";
  }
  return "?";
}

int16_t toWireReason(PlanStatus status) {
  switch (status) {
    case PlanStatus::kOk:
      return plan_result_t::REASON_NONE;
    case PlanStatus::kBadInput:
      return plan_result_t::REASON_BAD_INPUT;
    case PlanStatus::kNoMap:
      return plan_result_t::REASON_NO_MAP;
    case PlanStatus::kStartInObstacle:
      return plan_result_t::REASON_START_IN_OBSTACLE;
    case PlanStatus::kTargetInObstacle:
      return plan_result_t::REASON_TARGET_IN_OBSTACLE;
    case PlanStatus::kTargetOutOfBounds:
      return plan_result_t::REASON_TARGET_OUT_OF_BOUNDS;
    case PlanStatus::kInfeasibleStart:
      return plan_result_t::REASON_INFEASIBLE_START;
    case PlanStatus::kStartEqualsTarget:
      return plan_result_t::REASON_START_EQUALS_TARGET;
    case PlanStatus::kNoPath:
      return plan_result_t::REASON_NO_PATH;
    case PlanStatus::kCorridor:
      return plan_result_t::REASON_CORRIDOR;
    case PlanStatus::kOptimizer:
      return plan_result_t::REASON_OPTIMIZER;
    case PlanStatus::kVerify:
      return plan_result_t::REASON_VERIFY;
  }
  return plan_result_t::REASON_BAD_INPUT;
}

}  // namespace mmh
