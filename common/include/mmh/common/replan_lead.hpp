// The replan lead that goes with an answer deadline: a new trajectory takes effect this long
// after its request, keeping the configured margin over the deadline (the commit must still
// reach the vehicle). Shared by the arbiter's latency budget, which lengthens the deadline
// under load, and the start-up check that the vehicle can stop within its sensor's range at the
// longest lead the budget may use.
#pragma once

#include <algorithm>

namespace mmh {

inline double replanLeadFor(double answer_deadline_s, double configured_lead_s,
                            double configured_deadline_s) {
  const double margin_s = std::max(0.0, configured_lead_s - configured_deadline_s);
  return std::max(configured_lead_s, answer_deadline_s + margin_s);
}

}  // namespace mmh
