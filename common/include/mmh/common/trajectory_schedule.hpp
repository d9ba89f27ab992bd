// The committed trajectories a follower has been sent, in the order they take over: each at its
// own start time, a later commit replacing the queued ones that would start at or after its own
// start (the arbiter's rule: docs/architecture.md, "One trajectory type"). The simulated vehicle
// and mmh-setpoint both follow TRAJECTORY through it, so both switch at the same instants.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>

#include "mmh/common/trajectory.hpp"

namespace mmh {

struct ScheduledTrajectory {
  std::shared_ptr<const Trajectory> trajectory;  // empty: hold where the follower is at the start
  int64_t start_utime = 0;
  int64_t id = 0;
};

class TrajectorySchedule {
 public:
  void commit(std::shared_ptr<const Trajectory> trajectory, int64_t start_utime, int64_t id);
  // The next queued trajectory that starts at or before `utime`, removed from the queue; the
  // follower switches to it at max(its start, the follower's own time). nullopt when none is due.
  std::optional<ScheduledTrajectory> popDue(int64_t utime);
  bool hasQueued() const { return !queued_.empty(); }
  void clear() { queued_.clear(); }

 private:
  std::deque<ScheduledTrajectory> queued_;
};

}  // namespace mmh
