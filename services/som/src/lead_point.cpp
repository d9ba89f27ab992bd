#include "mmh/som/lead_point.hpp"

#include <cmath>

#include "mmh/common/collision_check.hpp"
#include "mmh/common/geofence.hpp"
#include "mmh/common/vehicle_limits.hpp"

namespace mmh::som {

bool turnsAwayFromVelocity(const KinematicState& start, const Eigen::Vector3d& first_path_point,
                           const LeadPointParams& params) {
  const double speed = start.velocity.norm();
  const Eigen::Vector3d leg = first_path_point - start.position;
  if (speed < params.min_speed_mps || leg.norm() < 1e-6) return false;
  const double cos_turn = start.velocity.dot(leg) / (speed * leg.norm());
  return cos_turn < std::cos(params.min_turn_deg * M_PI / 180.0);
}

std::optional<Eigen::Vector3d> leadPoint(const VoxelGrid& grid, const KinematicState& start,
                                         double max_acc_mps2, const Eigen::Vector3d& lo,
                                         const Eigen::Vector3d& hi, const LeadPointParams& params) {
  constexpr double kMinAheadM = 0.3;
  const double speed = start.velocity.norm();
  if (speed < 1e-6 || max_acc_mps2 <= 0.0) return std::nullopt;
  const Eigen::Vector3d dir = start.velocity / speed;
  for (double d = params.reach * stoppingDistance(speed, max_acc_mps2); d >= kMinAheadM;
       d -= grid.resolution()) {
    const Eigen::Vector3d q = start.position + d * dir;
    if (!insideBox(q, lo, hi) || !grid.containsPoint(q)) continue;
    if (!isSegmentFree(grid, start.position, q)) continue;
    return q;
  }
  return std::nullopt;
}

}  // namespace mmh::som
