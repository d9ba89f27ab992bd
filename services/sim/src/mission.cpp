#include "mmh/sim/mission.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "mmh/common/mission.hpp"
#include "mmh/common/polynomial.hpp"
#include "mmh/common/vehicle_limits.hpp"
#include "mmh/sim/shortest_path.hpp"

namespace mmh::sim {

double jerkEnergy(const Trajectory& trajectory, double t0, double t1) {
  double energy = 0.0, start = 0.0;
  for (const Piece& piece : trajectory.pieces()) {
    const double a = std::max(t0, start) - start;
    const double b = std::min(t1, start + piece.duration) - start;
    if (b > a) {
      // |jerk|^2 as a polynomial: jerk coefficient k is c_{k+3} (k+3)(k+2)(k+1).
      PolyCoeffs sum = PolyCoeffs::Zero(1);
      for (int axis = 0; axis < 3; ++axis) {
        PolyCoeffs j = PolyCoeffs::Zero(kMaxPolyOrder - 3);
        for (int k = 0; k + 3 < kMaxPolyOrder; ++k) {
          j[k] = piece.coeffs(axis, k + 3) * (k + 3) * (k + 2) * (k + 1);
        }
        sum = polyAdd(sum, polyMultiply(j, j));
      }
      energy += polyIntegral(sum, b) - polyIntegral(sum, a);
    }
    start += piece.duration;
  }
  return energy;
}

MissionMonitor::MissionMonitor(const World& world, const SimParams& params,
                               const Eigen::Vector3d& start, const Eigen::Vector3d& goal)
    : world_(world), params_(params) {
  metrics_.start = start;
  metrics_.goal = goal;
  arrival_point_ = goal;
  computeBound();
}

void MissionMonitor::computeBound() {
  metrics_.shortest_path_m =
      world_.shortestPathLength(metrics_.start, metrics_.goal, params_.vehicle_radius_m);
  metrics_.time_bound_s =
      restToRestTime(metrics_.shortest_path_m, params_.max_vel_mps, params_.max_acc_mps2);
}

void MissionMonitor::setGoal(const Eigen::Vector3d& goal, int64_t goal_id) {
  MissionGoal single;
  single.position = goal;
  single.goal_id = goal_id;
  setMissionGoal(single);
}

void MissionMonitor::setMissionGoal(const MissionGoal& goal) {
  metrics_.goal_id = goal.goal_id;
  metrics_.waypoint_index = goal.waypoint_index;
  metrics_.num_waypoints = goal.num_waypoints;
  const bool moved = (goal.position - metrics_.goal).norm() >= 1e-9;
  goal_ = goal;
  if (!moved) return;
  metrics_.goal = goal.position;
  arrival_point_ = goal.position;
  metrics_.goal_moved = false;
  metrics_.reached = false;
  metrics_.arrival_utime = -1;
  arrived_at_goal_ = false;
  if (goal.isLastWaypoint()) computeBound();
}

bool MissionMonitor::acceptMovedGoal(const Eigen::Vector3d& moved, double radius_m) {
  if (!moved.allFinite() || (moved - metrics_.goal).norm() > radius_m + 1e-6) return false;
  if (metrics_.reached) return true;  // already arrived: the metrics stay as they are
  arrival_point_ = moved;
  metrics_.goal_moved = true;
  metrics_.moved_goal = moved;
  return true;
}

bool MissionMonitor::goalReachedNow(const Eigen::Vector3d& position, double speed_mps) const {
  if (goal_.num_waypoints <= 1)
    return (position - arrival_point_).norm() <= params_.goal_tolerance_m;
  Waypoint w;
  w.position = arrival_point_;
  w.tolerance_m = goal_.tolerance_m > 0.0 ? goal_.tolerance_m : params_.goal_tolerance_m;
  w.stop = goal_.stop || goal_.isLastWaypoint();
  return waypointReached(w, position, speed_mps, params_.mission_stop_speed_mps);
}

bool MissionMonitor::update(int64_t now_utime, const Vehicle& vehicle,
                            const std::vector<FlownPart>& flown) {
  if (metrics_.reached) return false;
  bool event = false;
  for (const FlownPart& part : flown) {
    metrics_.distance_m += part.trajectory->arcLength(part.t0, part.t1);
    metrics_.energy += jerkEnergy(*part.trajectory, part.t0, part.t1);
  }
  if (vehicle.followsSetpoints()) {
    metrics_.follows_setpoints = true;
    metrics_.distance_m += vehicle.modelDistance() - model_distance_seen_m_;
    metrics_.energy += vehicle.modelEnergy() - model_energy_seen_;
    model_distance_seen_m_ = vehicle.modelDistance();
    model_energy_seen_ = vehicle.modelEnergy();
  }
  metrics_.distance_m += vehicle.jumpDistance() - jumps_seen_m_;
  jumps_seen_m_ = vehicle.jumpDistance();
  metrics_.trajectory_jumps = vehicle.jumps();
  if (!metrics_.started && vehicle.firstTrajectoryUtime() >= 0) {
    metrics_.started = true;
    metrics_.start_utime = vehicle.firstTrajectoryUtime();
  }
  if (metrics_.started) {
    metrics_.flight_time_s = 1e-6 * static_cast<double>(now_utime - metrics_.start_utime);
    if (const std::optional<double> error = vehicle.trackingError()) {
      tracking_error_sum_sq_ += *error * *error;
      ++metrics_.tracking_samples;
      metrics_.tracking_error_rms_m =
          std::sqrt(tracking_error_sum_sq_ / static_cast<double>(metrics_.tracking_samples));
      metrics_.tracking_error_max_m = std::max(metrics_.tracking_error_max_m, *error);
    }
  }
  const Eigen::Vector3d& p = vehicle.state().position;
  const double clearance = world_.clearance(p);
  metrics_.min_clearance_m = std::min(metrics_.min_clearance_m, clearance);
  if (!metrics_.collided && clearance < params_.vehicle_radius_m) {
    metrics_.collided = true;
    metrics_.collision_utime = now_utime;
    metrics_.collision_position = p;
    event = true;
  }
  const double speed = vehicle.state().velocity.norm();
  if (!metrics_.collided && !arrived_at_goal_ && goalReachedNow(p, speed)) {
    arrived_at_goal_ = true;
    event = true;
    if (goal_.num_waypoints > 1) {
      metrics_.arrivals.push_back(
          WaypointArrival{goal_.waypoint_index, metrics_.flight_time_s, speed});
    }
    if (goal_.isLastWaypoint()) {
      metrics_.reached = true;
      metrics_.arrival_utime = now_utime;
    }
  }
  return event;
}

}  // namespace mmh::sim
