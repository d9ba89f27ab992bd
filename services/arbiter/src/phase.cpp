#include "mmh/arbiter/phase.hpp"

namespace mmh::arbiter {

const char* toString(Phase phase) {
  switch (phase) {
    case Phase::kIdle:
      return "idle";
    case Phase::kNewGoal:
      return "new-goal";
    case Phase::kTracking:
      return "tracking";
    case Phase::kRecovering:
      return "recovering";
    case Phase::kReached:
      return "reached";
    case Phase::kUnreachable:
      return "unreachable";
  }
  return "?";
}

}  // namespace mmh::arbiter
