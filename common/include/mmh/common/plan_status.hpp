// The outcome of one planning request, shared by the three modes (FPM, SOM, EAM). The libraries
// report a PlanStatus; only the nodes turn it into a wire code (plan_status_wire.hpp,
// plan_result_t.REASON_*).
#pragma once

namespace mmh {

enum class PlanStatus {
  kOk,
  kBadInput,           // NaN/Inf, inconsistent request, start outside the window / geofence
  kNoMap,              // no usable map
  kStartInObstacle,    // start in an occupied cell (or blocked and unable to escape)
  kTargetInObstacle,   // target inside the inflated obstacles
  kTargetOutOfBounds,  // target (or a waypoint) outside the geofence or the map window
  kInfeasibleStart,    // start speed / acceleration beyond the (tolerated) limits
  kStartEqualsTarget,  // at rest on the target already: nothing to plan
  kNoPath,             // A* found no path (or ran out of its node budget)
  kCorridor,           // SOM: the safe flight corridor could not be built
  kOptimizer,          // the optimiser failed, or collisions were left after its last round
  kVerify,             // the result failed the independent verification
};

// Short name ("no path", "verification", ...), for details and logs.
const char* toString(PlanStatus status);

}  // namespace mmh
