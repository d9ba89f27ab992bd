#include "mmh/common/trajectory_schedule.hpp"

namespace mmh {

void TrajectorySchedule::commit(std::shared_ptr<const Trajectory> trajectory, int64_t start_utime,
                                int64_t id) {
  while (!queued_.empty() && queued_.back().start_utime >= start_utime) queued_.pop_back();
  queued_.push_back(ScheduledTrajectory{std::move(trajectory), start_utime, id});
}

std::optional<ScheduledTrajectory> TrajectorySchedule::popDue(int64_t utime) {
  if (queued_.empty() || queued_.front().start_utime > utime) return std::nullopt;
  ScheduledTrajectory next = std::move(queued_.front());
  queued_.pop_front();
  return next;
}

}  // namespace mmh
