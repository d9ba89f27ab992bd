#include "mmh/arbiter/retrace.hpp"

#include <algorithm>

#include "mmh/common/collision_check.hpp"
#include "mmh/common/minco.hpp"

namespace mmh::arbiter {
namespace {

constexpr double kMinStepM = 0.05;       // route points nearer than this to the one before merge
constexpr double kMinPieceS = 0.2;       // shortest piece
constexpr double kEndPieceFactor = 2.0;  // the first and last pieces: speeding up, slowing down
constexpr double kSlowerFactor = 1.15;   // durations grow by this until the limits hold
constexpr int kMaxSlowdowns = 30;

}  // namespace

std::optional<Trajectory> retraceTrajectory(const KinematicState& start,
                                            const std::vector<Eigen::Vector3d>& route,
                                            double speed_mps, double max_vel_mps,
                                            double max_acc_mps2) {
  if (route.size() < 2 || speed_mps <= 0.0) return std::nullopt;
  // Every flown point a waypoint: a curve through fewer rounds the corners of the way the
  // vehicle came, and that way may be a gap no wider than the airframe.
  std::vector<Eigen::Vector3d> points{start.position};
  for (size_t i = 1; i < route.size(); ++i) {
    if ((route[i] - points.back()).norm() >= kMinStepM) points.push_back(route[i]);
  }
  if (points.size() < 2) return std::nullopt;
  points.back() = route.back();  // the route ends where the back-off was found clear
  const int pieces = static_cast<int>(points.size()) - 1;
  Eigen::Matrix3d head, tail;
  head << start.position, start.velocity, start.acceleration;
  tail << points.back(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero();
  Eigen::Matrix3Xd inner(3, pieces - 1);
  for (int i = 1; i < pieces; ++i) inner.col(i - 1) = points[i];
  Eigen::VectorXd durations(pieces);
  for (int i = 0; i < pieces; ++i) {
    durations[i] = std::max(kMinPieceS, (points[i + 1] - points[i]).norm() / speed_mps);
  }
  durations[0] *= kEndPieceFactor;
  durations[pieces - 1] *= kEndPieceFactor;
  MincoJerk minco;
  minco.setConditions(head, tail, pieces);
  for (int k = 0; k < kMaxSlowdowns; ++k, durations *= kSlowerFactor) {
    minco.setParameters(inner, durations);
    Trajectory t = minco.trajectory();
    if (t.maxSpeed() <= max_vel_mps && t.maxAcceleration() <= max_acc_mps2) return t;
  }
  return std::nullopt;
}

bool keepsOffOccupied(const VoxelGrid& grid, const Trajectory& t, double min_distance_m,
                      double step_s) {
  for (double s = 0.0;; s = std::min(s + step_s, t.duration())) {
    if (!keepsEscapeDistance(grid, t.position(s), min_distance_m)) return false;
    if (s >= t.duration()) return true;
  }
}

}  // namespace mmh::arbiter
