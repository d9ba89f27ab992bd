#include "consume.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "mmh/common/checked_decode.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/msg_convert.hpp"
#include "mmh/common/trajectory.hpp"

namespace mmh::fuzz {
namespace {

// Inflation of the map consumers (map.inflation_m of deploy/config/default.yaml).
constexpr double kInflation_m = 0.3;

void require(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz invariant broken: %s\n", what);
    std::abort();
  }
}

// An accepted message encodes again to a buffer that decodes and validates to the same size.
template <class Msg>
void reencode(const Msg& msg) {
  const int size = msg.getEncodedSize();
  require(size > 0, "encoded size");
  std::vector<uint8_t> buf(static_cast<size_t>(size));
  require(msg.encode(buf.data(), 0, size) == size, "re-encode");
  Msg again;
  require(
      decodeChecked(buf.data(), static_cast<uint32_t>(size), again, nullptr) == DecodeOutcome::kOk,
      "re-decode of an accepted message");
  require(again.getEncodedSize() == size, "round trip size");
}

// The evaluations the arbiter, the simulator and the modes run on a received trajectory.
void exercise(const Trajectory& traj) {
  require(traj.isFinite(), "validated trajectory is not finite");
  const double d = traj.duration();
  require(std::isfinite(d) && d >= 0.0, "duration");
  for (double t : {-1.0, 0.0, 0.37 * d, d, d + 1.0}) {
    const KinematicState s = traj.state(t);
    (void)s;
    (void)traj.jerk(t);
  }
  (void)traj.maxSpeed();
  (void)traj.maxAcceleration();
  (void)traj.jerkEnergy();
  (void)traj.tail(0.5 * d);
  if (traj.numPieces() <= 64) (void)traj.arcLength();
}

}  // namespace

void consume(const odometry_t& msg) {
  reencode(msg);
  (void)stateOf(msg);
}

void consume(const pointcloud_t& msg) {
  reencode(msg);
}

void consume(const goal_t& msg) {
  reencode(msg);
}

void consume(const local_map_t& msg) {
  reencode(msg);
  LocalMapReceiver receiver(kInflation_m);
  if (msg.kind == local_map_t::KIND_DELTA) {
    // A delta needs the keyframe it applies on: an empty one of the same geometry, shifted.
    local_map_t key = msg;
    key.kind = local_map_t::KIND_KEYFRAME;
    key.map_seq = msg.base_seq;
    key.base_seq = 0;
    key.origin_index[0] = msg.origin_index[0] - 3;
    key.runs.clear();
    key.num_bytes = 0;
    key.num_changed = 0;
    if (key.map_seq > 0) receiver.apply(key);
  }
  std::string why;
  const LocalMapReceiver::Result r = receiver.apply(msg, &why);
  if (r != LocalMapReceiver::Result::kApplied) return;
  const VoxelGrid& grid = receiver.grid();
  require(grid.numCells() == int64_t{msg.size[0]} * msg.size[1] * msg.size[2], "grid size");
  const Eigen::Vector3d centre = 0.5 * (grid.minCorner() + grid.maxCorner());
  (void)grid.atPoint(centre);
  (void)grid.isBlockedPoint(centre);
  (void)grid.isOccupiedPoint(grid.minCorner());
}

void consume(const awareness_t& msg) {
  reencode(msg);
}

void consume(const trajectory_t& msg) {
  reencode(msg);
  exercise(fromMsg(msg));
}

void consume(const plan_request_t& msg) {
  reencode(msg);
  require(getWaypoints(msg).size() == msg.waypoints.size(), "waypoints");
  (void)startStateOf(msg);
  exercise(fromMsg(msg.reference));
}

void consume(const plan_result_t& msg) {
  reencode(msg);
  exercise(fromMsg(msg.trajectory));
}

void consume(const arbiter_status_t& msg) {
  reencode(msg);
}

void consume(const heartbeat_t& msg) {
  reencode(msg);
}

void consume(const mission_status_t& msg) {
  reencode(msg);
}

void consume(const setpoint_t& msg) {
  reencode(msg);
}

void consume(const plan_debug_t& msg) {
  reencode(msg);
}

}  // namespace mmh::fuzz
