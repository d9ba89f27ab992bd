// Watches progress toward the goal: how long the vehicle has gone without getting nearer to it
// than ever before (by more than a minimum step) or, optionally, onto new ground (farther than a
// distance from every place it has flown since the goal was set: a detour along a wall is
// progress; flying back and forth over the same places, or back the way it came, is not), and
// where it has flown recently (known free space to back off to). The arbiter's stuck detector reads
// it (replan_rules.hpp, stuckResponse): a flight that makes no progress changes strategy, then
// gives up with a reason, instead of repeating the same failing round without end.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <limits>
#include <optional>
#include <vector>

#include "mmh/common/voxel_grid.hpp"

namespace mmh::arbiter {

class ProgressMonitor {
 public:
  // new_ground_m 0: only getting nearer to the goal is progress.
  ProgressMonitor(double min_step_m, double history_s, double sample_period_s,
                  double new_ground_m = 0.0)
      : min_step_m_(min_step_m),
        history_s_(history_s),
        sample_period_s_(sample_period_s),
        new_ground_m_(new_ground_m) {}

  // A new goal (or a new chance after giving up): progress is counted from here.
  void restart(int64_t now);
  // One vehicle position, distance_to_goal_m away from the goal.
  void observe(int64_t now, const Eigen::Vector3d& position, double distance_to_goal_m);

  // Seconds since the distance to the goal last shrank by min_step_m below its best, or since the
  // vehicle last reached new ground.
  double secondsWithoutProgress(int64_t now) const;

  // The newest recently flown position at least min_distance_m from `from` that keeps
  // clearance_m from every occupied cell of `grid`: known free space to back off to.
  std::optional<Eigen::Vector3d> backOffPoint(const VoxelGrid& grid, const Eigen::Vector3d& from,
                                              double min_distance_m, double clearance_m) const;
  // The way the vehicle came, back to that point: `from`, then the positions flown since it,
  // newest first, at least spacing_m apart, ending at the point. Empty when there is none.
  std::vector<Eigen::Vector3d> backOffRoute(const VoxelGrid& grid, const Eigen::Vector3d& from,
                                            double min_distance_m, double clearance_m,
                                            double spacing_m) const;

 private:
  struct Sample {
    int64_t utime;
    Eigen::Vector3d position;
  };
  bool onNewGround(const Eigen::Vector3d& position) const;

  double min_step_m_, history_s_, sample_period_s_, new_ground_m_;
  double best_distance_m_ = std::numeric_limits<double>::infinity();
  int64_t last_progress_utime_ = 0;
  std::deque<Sample> history_;  // newest last
  // Places flown since the goal was set, each new_ground_m from the others.
  std::vector<Eigen::Vector3d> ground_;
};

}  // namespace mmh::arbiter
