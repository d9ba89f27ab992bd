// The nodes' mapping of the planners' PlanStatus to the wire codes plan_result_t.REASON_*
// (the libraries never see the wire codes).
#pragma once

#include <cstdint>

#include "mmh/common/plan_status.hpp"

namespace mmh {

int16_t toWireReason(PlanStatus status);

}  // namespace mmh
