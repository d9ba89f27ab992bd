// Conversions between the project's Eigen/Trajectory types and the LCM messages. Messages with
// nested arrays are filled only through these checked helpers (lcm-gen's encoder does not check
// inner sizes, see docs/architecture.md, "Message types").
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mmh/common/plan_debug.hpp"
#include "mmh/common/trajectory.hpp"
#include "mmh/odometry_t.hpp"
#include "mmh/plan_debug_t.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/trajectory_t.hpp"

namespace mmh {

inline Eigen::Vector3d toVec3(const double v[3]) {
  return Eigen::Vector3d(v[0], v[1], v[2]);
}
inline void fromVec3(const Eigen::Vector3d& v, double out[3]) {
  out[0] = v.x();
  out[1] = v.y();
  out[2] = v.z();
}

// Pieces of `traj` into `msg` (num_pieces and pieces; header, id and start time are the caller's).
void toMsg(const Trajectory& traj, trajectory_t& msg);
Trajectory fromMsg(const trajectory_t& msg);

void setWaypoints(const std::vector<Eigen::Vector3d>& points, plan_request_t& msg);
std::vector<Eigen::Vector3d> getWaypoints(const plan_request_t& msg);

KinematicState startStateOf(const plan_request_t& msg);
void setStartState(const KinematicState& state, plan_request_t& msg);
KinematicState stateOf(const odometry_t& msg);

// The PLAN_DEBUG message of one answer (the header is the publisher's).
plan_debug_t toDebugMsg(const PlanDebug& debug, int64_t request_id, int8_t mode, bool ok);

}  // namespace mmh
