// The arbiter's phase: what it is doing with the current goal while no planning round is in
// flight. A round in flight (requests sent, answers awaited) is held beside the phase; its
// decision moves the phase on (a commit to kTracking, a failure to kRecovering).
//
//   kIdle ──goal──► kNewGoal ──round starts──► kTracking ◄──commit── kRecovering
//                                                  │   ──failure / stop──►  ▲
//                                                  └──── at the goal ──► kReached
// No progress toward the goal for arbiter.give_up_s: kUnreachable (holding, an occasional retry;
// a commit returns to kTracking). A new goal returns every phase to kNewGoal.
#pragma once

namespace mmh::arbiter {

enum class Phase {
  kIdle,         // no goal yet
  kNewGoal,      // a goal (or a moved one) not planned for yet: the next round is for it
  kTracking,     // following the committed trajectory (or none yet); lazy rules decide replans
  kRecovering,   // the last round failed or a stop was committed: the fallback chain goes on
  kReached,      // at the goal on a trajectory that ends there: nothing more to do
  kUnreachable,  // no progress for give_up_s: holding, retrying every unreachable_retry_s
};

const char* toString(Phase phase);

}  // namespace mmh::arbiter
