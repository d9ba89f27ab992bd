#include "mmh/arbiter/answer_check.hpp"

#include <algorithm>

#include "mmh/common/collision_check.hpp"

namespace mmh::arbiter {

bool checkAnswer(const Trajectory& t, int64_t answer_start_utime, const RequestedStart& requested,
                 const VoxelGrid* grid, const ArbiterParams& params, std::string* why) {
  const KinematicState& start = requested.state;
  auto fail = [&](const std::string& text) {
    if (why) *why = text;
    return false;
  };
  if (t.empty() || !t.isFinite()) return fail("empty or non-finite trajectory");
  if (t.duration() > params.max_answer_duration_s) return fail("longer than max_answer_duration_s");
  if (answer_start_utime != requested.start_utime) return fail("wrong start time");
  const KinematicState s0 = t.state(0.0);
  // Continuity: the new trajectory must take over the committed one without a jump.
  if ((s0.position - start.position).norm() > params.start_position_tolerance_m ||
      (s0.velocity - start.velocity).norm() > params.start_velocity_tolerance_mps ||
      (s0.acceleration - start.acceleration).norm() > params.start_acceleration_tolerance_mps2) {
    return fail("does not start at the requested state");
  }
  const double tol = 1.0 + params.answer_speed_tolerance;
  const double start_speed = start.velocity.norm();
  if (t.maxSpeed() > std::max(params.max_vel_mps, start_speed) * tol) return fail("too fast");
  if (t.maxAcceleration() > params.max_acc_mps2 * tol) {
    // A braking start may exceed a_max briefly only if it already did.
    if (t.maxAcceleration() > std::max(params.max_acc_mps2, start.acceleration.norm()) * tol)
      return fail("accelerates too hard");
  }
  for (double time = 0.0; time <= t.duration(); time += params.check_step_s) {
    const Eigen::Vector3d p = t.position(time);
    if ((p.array() < params.geofence_min_m.array() - params.geofence_tolerance_m).any() ||
        (p.array() > params.geofence_max_m.array() + params.geofence_tolerance_m).any()) {
      return fail("leaves the geofence");
    }
  }
  double clear_from = 0.0;
  if (grid && isPointBlocked(*grid, s0.position)) {
    // A start inside the margin (e.g. stopped next to a newly mapped obstacle) may leave it, as
    // the planners allow: through no occupied voxel, out of the margin near the start.
    if (firstCollisionTime(*grid, t, 0.0, t.duration(), CollisionLayer::kOccupied)) {
      return fail("enters an obstacle");
    }
    // Outwards only: never nearer to the occupied cells than the start (or than the check
    // margin), or a vehicle next to an obstacle is re-planned along it until it touches it.
    const double min_distance = escapeMinDistance(*grid, s0.position, params.check_inflation_m);
    while (clear_from < t.duration() && isPointBlocked(*grid, t.position(clear_from))) {
      if (!keepsEscapeDistance(*grid, t.position(clear_from), min_distance,
                               params.escape_depth_tolerance_m)) {
        return fail("goes deeper into the obstacle margin it starts in");
      }
      clear_from += params.escape_step_s;
    }
    if ((t.position(clear_from) - s0.position).norm() > params.start_escape_radius_m) {
      return fail("does not leave the obstacle margin near its start");
    }
  }
  if (grid && firstCollisionTime(*grid, t, clear_from, t.duration()).has_value()) {
    return fail("collides with the arbiter's map");
  }
  return true;
}

}  // namespace mmh::arbiter
