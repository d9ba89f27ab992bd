#include "mmh/arbiter/progress_monitor.hpp"

#include "mmh/arbiter/local_target.hpp"

namespace mmh::arbiter {

void ProgressMonitor::restart(int64_t now) {
  best_distance_m_ = std::numeric_limits<double>::infinity();
  last_progress_utime_ = now;
  ground_.clear();
}

bool ProgressMonitor::onNewGround(const Eigen::Vector3d& position) const {
  for (const Eigen::Vector3d& place : ground_) {
    if ((place - position).norm() < new_ground_m_) return false;
  }
  return true;
}

void ProgressMonitor::observe(int64_t now, const Eigen::Vector3d& position,
                              double distance_to_goal_m) {
  if (distance_to_goal_m < best_distance_m_ - min_step_m_ ||
      best_distance_m_ == std::numeric_limits<double>::infinity()) {
    best_distance_m_ = distance_to_goal_m;
    last_progress_utime_ = now;
  }
  if (new_ground_m_ > 0.0 && onNewGround(position)) {
    last_progress_utime_ = now;
    ground_.push_back(position);
  }
  if (history_.empty() || (now - history_.back().utime) * 1e-6 >= sample_period_s_) {
    history_.push_back({now, position});
  }
  while (!history_.empty() && (now - history_.front().utime) * 1e-6 > history_s_) {
    history_.pop_front();
  }
}

double ProgressMonitor::secondsWithoutProgress(int64_t now) const {
  return (now - last_progress_utime_) * 1e-6;
}

std::optional<Eigen::Vector3d> ProgressMonitor::backOffPoint(const VoxelGrid& grid,
                                                             const Eigen::Vector3d& from,
                                                             double min_distance_m,
                                                             double clearance_m) const {
  for (auto it = history_.rbegin(); it != history_.rend(); ++it) {
    if ((it->position - from).norm() >= min_distance_m &&
        isClearOf(grid, it->position, clearance_m))
      return it->position;
  }
  return std::nullopt;
}

std::vector<Eigen::Vector3d> ProgressMonitor::backOffRoute(const VoxelGrid& grid,
                                                           const Eigen::Vector3d& from,
                                                           double min_distance_m,
                                                           double clearance_m,
                                                           double spacing_m) const {
  std::vector<Eigen::Vector3d> route{from};
  for (auto it = history_.rbegin(); it != history_.rend(); ++it) {
    const bool last = (it->position - from).norm() >= min_distance_m &&
                      isClearOf(grid, it->position, clearance_m);
    if (last || (it->position - route.back()).norm() >= spacing_m) route.push_back(it->position);
    if (last) return route;
  }
  return {};
}

}  // namespace mmh::arbiter
