// Vocabulary of the arbiter: planning modes, replanning triggers and decision outcomes. The
// numeric values equal the LCM constants (plan_request_t.MODE_*, arbiter_status_t.TRIGGER_* and
// OUTCOME_*), so the node converts by a cast.
#pragma once

#include <cstdint>

namespace mmh::arbiter {

enum class Mode : int8_t { kNone = 0, kFpm = 1, kSom = 2, kEam = 3, kStop = 4 };

enum class Trigger : int8_t {
  kNone = 0,
  kInitial = 1,    // first plan for a goal
  kHalfway = 2,    // committed trajectory executed past its halfway point
  kCollision = 3,  // newly mapped obstacle on the rest of the committed trajectory
  kGoalChanged = 4,
  kRetry = 5,  // the last attempt failed
  kFixed = 6,  // fixed-distance replanning (baselines)
};

enum class Outcome : int8_t {
  kCommitted = 1,
  kFailed = 2,
  kStopping = 3,
  kReached = 4,
  kRejected = 5,
  kUnreachable = 6,
  kGoalMoved = 7,  // the goal lay in an obstacle's margin: moved to the nearest free point
  kKept = 8,       // a halfway answer would reach the goal later: the committed one stays
};

const char* toString(Mode mode);
const char* toString(Trigger trigger);
const char* toString(Outcome outcome);

// Index of per-mode arrays (size 5: none, FPM, SOM, EAM, stop).
inline int modeIndex(Mode mode) {
  return static_cast<int>(mode);
}

inline uint8_t modeBit(Mode mode) {
  return static_cast<uint8_t>(1u << static_cast<int>(mode));
}

}  // namespace mmh::arbiter
