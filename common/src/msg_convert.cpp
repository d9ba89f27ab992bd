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

namespace {
void appendXyz(const Eigen::Vector3d& v, std::vector<float>& out) {
  for (int a = 0; a < 3; ++a) out.push_back(static_cast<float>(v[a]));
}
int32_t count(size_t n) {
  return static_cast<int32_t>(n);
}
}  // namespace

plan_debug_t toDebugMsg(const PlanDebug& debug, int64_t request_id, int8_t mode, bool ok) {
  plan_debug_t msg{};
  msg.request_id = request_id;
  msg.mode = mode;
  msg.ok = ok;
  for (const auto& path : debug.paths) {
    msg.path_points.push_back(count(path.size()));
    for (const Eigen::Vector3d& p : path) appendXyz(p, msg.path_xyz);
  }
  for (const auto& h : debug.polytopes) {
    msg.polytope_faces.push_back(static_cast<int32_t>(h.rows()));
    for (Eigen::Index r = 0; r < h.rows(); ++r)
      for (int c = 0; c < 4; ++c) msg.faces.push_back(static_cast<float>(h(r, c)));
  }
  for (const Eigen::Vector3d& q : debug.control_points) appendXyz(q, msg.control_xyz);
  for (const PlanDebug::AnchorPair& pair : debug.pairs) {
    msg.pair_control_point.push_back(pair.control_point);
    appendXyz(pair.p, msg.pair_p);
    appendXyz(pair.v, msg.pair_v);
  }
  msg.num_paths = count(msg.path_points.size());
  msg.num_path_coords = count(msg.path_xyz.size());
  msg.num_polytopes = count(msg.polytope_faces.size());
  msg.num_face_values = count(msg.faces.size());
  msg.num_control_coords = count(msg.control_xyz.size());
  msg.num_pairs = count(msg.pair_control_point.size());
  msg.num_pair_coords = count(msg.pair_p.size());
  return msg;
}

}  // namespace mmh
