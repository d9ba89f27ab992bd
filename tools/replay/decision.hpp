// One arbiter decision as mmh-replay compares it: the fields that say what the arbiter decided
// (trigger, outcome, modes asked, committed mode) plus where and when, for the report.
#pragma once

#include <string>

#include "mmh/arbiter_status_t.hpp"

namespace mmh {

struct Decision {
  double t_s = 0.0;  // message time since the first replayed input
  long long seq = 0;
  int trigger = 0, outcome = 0, modes_asked = 0, committed_mode = 0;
  double x = 0.0, y = 0.0, z = 0.0;
  std::string detail;

  // Two decisions match when they agree on trigger, outcome, modes asked and committed mode.
  bool sameAs(const Decision& other) const {
    return trigger == other.trigger && outcome == other.outcome &&
           modes_asked == other.modes_asked && committed_mode == other.committed_mode;
  }
  // "#12 5.23 s halfway -> committed SOM (asked SOM+EAM) at (3.1, 0.2, 1.2)"
  std::string describe() const;
};

Decision decisionOf(const arbiter_status_t& msg, long long t0_us);

}  // namespace mmh
