#include "mmh/common/decision_names.hpp"

#include "mmh/arbiter_status_t.hpp"
#include "mmh/heartbeat_t.hpp"
#include "mmh/plan_request_t.hpp"

namespace mmh {

const char* modeName(int mode) {
  switch (mode) {
    case 0:
      return "-";
    case plan_request_t::MODE_FPM:
      return "FPM";
    case plan_request_t::MODE_SOM:
      return "SOM";
    case plan_request_t::MODE_EAM:
      return "EAM";
    case plan_request_t::MODE_STOP:
      return "STOP";
  }
  return "?";
}

const char* triggerName(int trigger) {
  static const char* names[] = {"none", "initial", "halfway", "collision",
                                "goal", "retry",   "fixed"};
  return trigger >= 0 && trigger <= arbiter_status_t::TRIGGER_FIXED ? names[trigger] : "?";
}

const char* outcomeName(int outcome) {
  switch (outcome) {
    case arbiter_status_t::OUTCOME_COMMITTED:
      return "committed";
    case arbiter_status_t::OUTCOME_FAILED:
      return "failed";
    case arbiter_status_t::OUTCOME_STOPPING:
      return "stopping";
    case arbiter_status_t::OUTCOME_REACHED:
      return "reached";
    case arbiter_status_t::OUTCOME_REJECTED:
      return "rejected";
    case arbiter_status_t::OUTCOME_UNREACHABLE:
      return "unreachable";
    case arbiter_status_t::OUTCOME_GOAL_MOVED:
      return "goal-moved";
    case arbiter_status_t::OUTCOME_KEPT:
      return "kept";
  }
  return "?";
}

std::string modesMaskName(int mask) {
  std::string out;
  for (int mode = plan_request_t::MODE_FPM; mode <= plan_request_t::MODE_STOP; ++mode) {
    if (mask & (1 << mode)) {
      if (!out.empty()) out += "+";
      out += modeName(mode);
    }
  }
  return out.empty() ? "-" : out;
}

const char* heartbeatStateName(int state) {
  switch (state) {
    case heartbeat_t::STATE_STARTING:
      return "STARTING";
    case heartbeat_t::STATE_OK:
      return "OK";
    case heartbeat_t::STATE_DEGRADED:
      return "DEGRADED";
    case heartbeat_t::STATE_STOPPING:
      return "STOPPING";
  }
  return "?";
}

}  // namespace mmh
