#include "mmh/common/msg_convert.hpp"

namespace mmh {

void toMsg(const Trajectory& traj, trajectory_t& msg) {
  msg.num_pieces = traj.numPieces();
  msg.pieces.resize(traj.numPieces());
  for (int i = 0; i < traj.numPieces(); ++i) {
    const Piece& p = traj.pieces()[i];
    traj_piece_t& out = msg.pieces[i];
    out.duration_s = p.duration;
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k < kMaxPolyOrder; ++k) out.coeffs[a][k] = p.coeffs(a, k);
  }
}

Trajectory fromMsg(const trajectory_t& msg) {
  Trajectory traj;
  for (const traj_piece_t& in : msg.pieces) {
    Piece p;
    p.duration = in.duration_s;
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k < kMaxPolyOrder; ++k) p.coeffs(a, k) = in.coeffs[a][k];
    traj.append(p);
  }
  return traj;
}

void setWaypoints(const std::vector<Eigen::Vector3d>& points, plan_request_t& msg) {
  msg.num_waypoints = static_cast<int32_t>(points.size());
  msg.waypoints.assign(points.size(), std::vector<double>(3, 0.0));
  for (size_t i = 0; i < points.size(); ++i) {
    for (int a = 0; a < 3; ++a) msg.waypoints[i][a] = points[i][a];
  }
}

std::vector<Eigen::Vector3d> getWaypoints(const plan_request_t& msg) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& w : msg.waypoints) {
    if (w.size() == 3) out.emplace_back(w[0], w[1], w[2]);
  }
  return out;
}

KinematicState startStateOf(const plan_request_t& msg) {
  return KinematicState{toVec3(msg.start_position), toVec3(msg.start_velocity),
                        toVec3(msg.start_acceleration)};
}

void setStartState(const KinematicState& state, plan_request_t& msg) {
  fromVec3(state.position, msg.start_position);
  fromVec3(state.velocity, msg.start_velocity);
  fromVec3(state.acceleration, msg.start_acceleration);
}

KinematicState stateOf(const odometry_t& msg) {
  return KinematicState{toVec3(msg.position), toVec3(msg.velocity), toVec3(msg.acceleration)};
}

}  // namespace mmh
