#include "decision.hpp"

#include <cstdio>

#include "mmh/common/decision_names.hpp"

namespace mmh {

std::string Decision::describe() const {
  char text[256];
  std::snprintf(text, sizeof(text), "#%lld %.2f s %s -> %s %s (asked %s) at (%.1f, %.1f, %.1f)",
                seq, t_s, triggerName(trigger), outcomeName(outcome), modeName(committed_mode),
                modesMaskName(modes_asked).c_str(), x, y, z);
  return text;
}

Decision decisionOf(const arbiter_status_t& msg, long long t0_us) {
  Decision d;
  d.t_s = (msg.header.utime - t0_us) * 1e-6;
  d.seq = msg.decision_seq;
  d.trigger = msg.trigger;
  d.outcome = msg.outcome;
  d.modes_asked = msg.modes_asked;
  d.committed_mode = msg.committed_mode;
  d.x = msg.position[0];
  d.y = msg.position[1];
  d.z = msg.position[2];
  d.detail = msg.detail;
  return d;
}

}  // namespace mmh
