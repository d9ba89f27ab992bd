#include "mmh/arbiter/answer_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mmh/common/collision_check.hpp"
#include "mmh/common/trajectory_verifier.hpp"
#include "mmh/common/vehicle_limits.hpp"

namespace mmh::arbiter {
namespace {

// The arbiter's words for the shared verifier's checks.
const char* arbiterWords(VerifyCheck check) {
  switch (check) {
    case VerifyCheck::kNotFinite:
      return "empty or non-finite trajectory";
    case VerifyCheck::kStartState:
      return "does not start at the requested state";
    case VerifyCheck::kSpeed:
      return "too fast";
    case VerifyCheck::kAcceleration:
      return "accelerates too hard";
    case VerifyCheck::kGeofence:
      return "leaves the geofence";
    case VerifyCheck::kOccupied:
      return "enters an obstacle";
    case VerifyCheck::kEscapeDeeper:
      return "goes deeper into the obstacle margin it starts in";
    case VerifyCheck::kEscapeTooFar:
      return "does not leave the obstacle margin near its start";
    case VerifyCheck::kInflated:
      return "collides with the arbiter's map";
    default:
      return toString(check);
  }
}

}  // namespace

double knownSpaceHorizonM(double start_speed_mps, const ArbiterParams& params) {
  return stoppingDistance(start_speed_mps, params.max_acc_mps2) + params.known_space_margin_m;
}

namespace {

// firstUnknownWithin, with or without the centre line.
std::optional<double> firstUnmapped(const Trajectory& t, const VoxelGrid& grid, double horizon_m,
                                    double step_s, const BesideThePath& beside, bool centre_line,
                                    UnmappedCell* where) {
  const Eigen::Vector3d start = t.position(0.0);
  const Eigen::Vector3i start_cell = grid.localIndexOf(start);
  const double res = grid.resolution();
  const bool check_beside = beside.radius_m > 0.0 && beside.hidden_face_m > 0.0;
  const int beside_cells = static_cast<int>(std::ceil(beside.radius_m / res));
  const double radius_sq = beside.radius_m * beside.radius_m;
  // Squared distance from p to the nearest point of the cell `local`.
  auto cellDistanceSq = [&](const Eigen::Vector3i& local, const Eigen::Vector3d& p) {
    const Eigen::Vector3d lo = grid.centerOfLocal(local).array() - 0.5 * res;
    const Eigen::Vector3d gap = (lo - p).cwiseMax(p - lo - Eigen::Vector3d::Constant(res));
    return gap.cwiseMax(0.0).squaredNorm();
  };
  // An occupied cell within hidden_face_m of `cell`, in its layer or the two next to it.
  const int face_cells = static_cast<int>(std::ceil(beside.hidden_face_m / res));
  const double face_sq = beside.hidden_face_m * beside.hidden_face_m;
  auto nearMappedObstacle = [&](const Eigen::Vector3i& cell) {
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -face_cells; dy <= face_cells; ++dy)
        for (int dx = -face_cells; dx <= face_cells; ++dx) {
          if ((dx * dx + dy * dy) * res * res > face_sq + 1e-9) continue;
          const Eigen::Vector3i other = cell + Eigen::Vector3i(dx, dy, dz);
          if (grid.inWindow(other) && grid.at(other) == Occupancy::kOccupied) return true;
        }
    return false;
  };
  // Whether a mapped obstacle stands between the start and `cell`: then the cell is in its
  // shadow, which the sensor sees on the way, not a side it never looked at.
  auto inShadow = [&](const Eigen::Vector3i& cell) {
    const Eigen::Vector3d to = grid.centerOfLocal(cell);
    const double length = (to - start).norm();
    const int steps = static_cast<int>(std::ceil(length / (0.5 * res)));
    for (int i = 1; i < steps; ++i) {
      const Eigen::Vector3i on = grid.localIndexOf(start + (to - start) * (double(i) / steps));
      if (on == cell) break;
      if (grid.inWindow(on) && grid.at(on) == Occupancy::kOccupied) return true;
    }
    return false;
  };
  auto besideHiddenFace = [&](const Eigen::Vector3d& p, const Eigen::Vector3i& centre, bool near,
                              Eigen::Vector3i* found) {
    for (int dy = -beside_cells; dy <= beside_cells; ++dy)
      for (int dx = -beside_cells; dx <= beside_cells; ++dx) {
        const Eigen::Vector3i cell = centre + Eigen::Vector3i(dx, dy, 0);
        if (!grid.inWindow(cell) || grid.at(cell) != Occupancy::kUnknown) continue;
        if (cellDistanceSq(cell, p) > radius_sq) continue;
        // The airframe's own cells at the start: where it is now, seen or not.
        if (cellDistanceSq(cell, start) <= radius_sq) continue;
        if (nearMappedObstacle(cell) && (near || !inShadow(cell))) {
          *found = cell;
          return true;
        }
      }
    return false;
  };
  double travelled = 0.0;
  Eigen::Vector3d previous = start;
  for (double s = 0.0; s <= t.duration() && travelled <= horizon_m; s += step_s) {
    const Eigen::Vector3d p = t.position(s);
    travelled += (p - previous).norm();
    previous = p;
    const Eigen::Vector3i cell = grid.localIndexOf(p);
    // The vehicle's own cell: where it is now, seen or not.
    if (centre_line && cell != start_cell && grid.inWindow(cell) &&
        grid.at(cell) == Occupancy::kUnknown) {
      if (where) *where = {grid.centerOfLocal(cell), false};
      return s;
    }
    Eigen::Vector3i beside_cell;
    if (check_beside && besideHiddenFace(p, cell, travelled <= beside.reach_m, &beside_cell)) {
      if (where) *where = {grid.centerOfLocal(beside_cell), true};
      return s;
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<double> firstUnknownWithin(const Trajectory& t, const VoxelGrid& grid,
                                         double horizon_m, double step_s,
                                         const BesideThePath& beside, UnmappedCell* where) {
  return firstUnmapped(t, grid, horizon_m, step_s, beside, true, where);
}

bool touchesHiddenFace(const Trajectory& stop, const VoxelGrid& grid, const ArbiterParams& params) {
  const double length_m = stop.arcLength();
  return firstUnmapped(stop, grid, length_m, params.check_step_s,
                       {params.vehicle_radius_m, params.hidden_face_m, length_m}, false, nullptr)
      .has_value();
}

std::optional<double> firstUnknownWithinReach(const Trajectory& t, double elapsed_s, double lead_s,
                                              const VoxelGrid& grid, const ArbiterParams& params,
                                              UnmappedCell* where) {
  if (t.empty() || elapsed_s >= t.duration()) return std::nullopt;
  const double lead_end_s = std::min(t.duration(), elapsed_s + lead_s);
  const double horizon_m = t.arcLength(elapsed_s, lead_end_s) +
                           knownSpaceHorizonM(t.velocity(lead_end_s).norm(), params);
  const auto at = firstUnknownWithin(
      t.tail(elapsed_s), grid, horizon_m, params.check_step_s,
      {params.vehicle_radius_m, params.hidden_face_m, params.hidden_face_reach_m}, where);
  if (!at) return std::nullopt;
  return elapsed_s + *at;
}

std::string describeUnmappedCell(const UnmappedCell& cell) {
  char text[112];
  std::snprintf(text, sizeof(text), "at (%.2f, %.2f, %.2f)%s", cell.center.x(), cell.center.y(),
                cell.center.z(),
                cell.beside_path ? ", an obstacle's unseen side beside its path" : " on its path");
  return text;
}

bool checkAnswer(const Trajectory& t, int64_t answer_start_utime, const RequestedStart& requested,
                 const VoxelGrid* grid, const ArbiterParams& params, double reach_lead_s,
                 std::string* why) {
  const KinematicState& start = requested.state;
  auto fail = [&](const std::string& text) {
    if (why) *why = text;
    return false;
  };
  if (t.empty() || !t.isFinite()) return fail("empty or non-finite trajectory");
  if (t.duration() > params.max_answer_duration_s) return fail("longer than max_answer_duration_s");
  if (answer_start_utime != requested.start_utime) return fail("wrong start time");
  // The shared verifier (mmh/common/trajectory_verifier.hpp) with the arbiter's tolerances and
  // its time-step sampling.
  VerifierOptions o;
  // Continuity: the new trajectory must take over the committed one without a jump.
  o.check_start = true;
  o.start = start;
  o.start_position_tol_m = params.start_position_tolerance_m;
  o.start_velocity_tol_mps = params.start_velocity_tolerance_mps;
  o.start_acceleration_tol_mps2 = params.start_acceleration_tolerance_mps2;
  // A start above a limit (e.g. braking) may keep it, but not exceed it.
  o.check_limits = true;
  o.max_vel_mps =
      std::max(speedLimitFor(requested.max_speed_mps, params.max_vel_mps), start.velocity.norm());
  o.max_acc_mps2 = std::max(params.max_acc_mps2, start.acceleration.norm());
  o.limit_relative_tol = params.answer_speed_tolerance;
  o.maxima = MaximaMethod::kStationaryPoints;
  o.check_geofence = true;
  o.geofence_min = params.geofence_min_m;
  o.geofence_max = params.geofence_max_m;
  o.geofence_tol_m = params.geofence_tolerance_m;
  o.sampling = VerifierOptions::Sampling::kTimeSteps;
  o.time_step_s = params.check_step_s;
  o.escape_step_s = params.escape_step_s;
  o.grid = grid;  // null: no map yet, no collision checks
  o.check_inflated = true;
  // A start inside the margin (e.g. stopped next to a newly mapped obstacle) may leave it, as
  // the planners allow: through no occupied voxel, out of the margin near the start, and
  // outwards only, never nearer to the occupied cells than the start (or than the check
  // margin), or a vehicle next to an obstacle is re-planned along it until it touches it.
  o.escape_radius_m = params.start_escape_radius_m;
  o.escape_depth_tol_m = params.escape_depth_tolerance_m;
  if (grid)
    o.escape_min_distance_m = escapeMinDistance(*grid, t.position(0.0), params.check_inflation_m);
  const VerifyResult v = verifyTrajectory(t, o);
  if (!v.ok) {
    if (!isCollision(v.failed) && v.failed != VerifyCheck::kGeofence)
      return fail(arbiterWords(v.failed));
    // Where: a rejection the user can find in the map.
    const Eigen::Vector3d p = t.position(v.at_time);
    char where[96];
    std::snprintf(where, sizeof(where), " %.2f s from its start, at (%.2f, %.2f, %.2f)", v.at_time,
                  p.x(), p.y(), p.z());
    return fail(arbiterWords(v.failed) + std::string(where));
  }
  // The stop from where the answer is when the next map can check it again must end in space
  // the sensor has seen: an answer accelerating from rest reaches farther than its start speed.
  if (grid) {
    UnmappedCell where;
    if (const auto at = firstUnknownWithinReach(t, 0.0, reach_lead_s, *grid, params, &where)) {
      char text[64];
      std::snprintf(text, sizeof(text), "enters unmapped space %.2f s from its start, ", *at);
      return fail(text + describeUnmappedCell(where));
    }
  }
  return true;
}

}  // namespace mmh::arbiter
