#include "mmh/arbiter/modes.hpp"

namespace mmh::arbiter {

const char* toString(Mode mode) {
  switch (mode) {
    case Mode::kNone:
      return "none";
    case Mode::kFpm:
      return "FPM";
    case Mode::kSom:
      return "SOM";
    case Mode::kEam:
      return "EAM";
    case Mode::kStop:
      return "STOP";
  }
  return "?";
}

const char* toString(Trigger trigger) {
  switch (trigger) {
    case Trigger::kNone:
      return "none";
    case Trigger::kInitial:
      return "initial";
    case Trigger::kHalfway:
      return "halfway";
    case Trigger::kCollision:
      return "collision";
    case Trigger::kGoalChanged:
      return "goal-changed";
    case Trigger::kRetry:
      return "retry";
    case Trigger::kFixed:
      return "fixed-distance";
  }
  return "?";
}

const char* toString(Outcome outcome) {
  switch (outcome) {
    case Outcome::kCommitted:
      return "committed";
    case Outcome::kFailed:
      return "failed";
    case Outcome::kStopping:
      return "stopping";
    case Outcome::kReached:
      return "reached";
    case Outcome::kRejected:
      return "rejected";
    case Outcome::kUnreachable:
      return "unreachable";
    case Outcome::kGoalMoved:
      return "goal-moved";
    case Outcome::kKept:
      return "kept";
  }
  return "?";
}

}  // namespace mmh::arbiter
