// The arbiter's own check of a mode's answer before it may be committed: it trusts no mode. An
// answer must take over the committed trajectory without a jump at the requested start, keep
// the limits, stay in the geofence and collide with nothing in the arbiter's map (a start inside
// the check margin may leave it, outwards and near the start only) - and its reach must lie in
// space the sensor has seen: the path until the next map can check it again, then the stretch in
// which the vehicle could stop from the speed there (plus a margin). Planners treat unknown space
// as free, which is safe far ahead but not where the vehicle will be before it could brake
// (sideways, backwards or down, where a forward camera never looked). Beside the centre line,
// within the airframe's radius, unknown cells next to a mapped obstacle count too: they may be the
// obstacle's side the sensor has not seen.
#pragma once

#include <optional>
#include <string>

#include "mmh/arbiter/arbiter_params.hpp"
#include "mmh/common/trajectory.hpp"
#include "mmh/common/voxel_grid.hpp"

namespace mmh::arbiter {

// What was asked: the answer must start at start_utime in exactly this state, and fly no faster
// than max_speed_mps (0: the vehicle's max_vel_mps).
struct RequestedStart {
  int64_t start_utime = 0;
  KinematicState state;
  double max_speed_mps = 0.0;
};

// The distance from the start within which an answer must stay in mapped space: the stopping
// distance from start_speed_mps at max_acc_mps2 plus known_space_margin_m.
double knownSpaceHorizonM(double start_speed_mps, const ArbiterParams& params);

// Unknown cells beside the centre line that count: those the airframe (radius_m, in the path's
// voxel layer) would touch and that lie within hidden_face_m of an occupied cell - the side of a
// mapped obstacle the sensor has not seen. Other unknown cells beside the path do not: a forward
// camera never sees beside its own body, and a vehicle whose plan turns could never leave.
// Farther than reach_m of path from the start, only cells in plain sight of the start (no
// occupied cell between): a side the sensor could see from there but never looked at, which a
// forward camera will not see on the way either. A cell in an obstacle's shadow it sees on the
// way, as it passes the obstacle the path swerves round. hidden_face_m 0: the centre line only.
struct BesideThePath {
  double radius_m = 0.0;
  double hidden_face_m = 0.0;
  double reach_m = 0.0;
};

// Where a trajectory meets unmapped space: the unknown cell's centre, and whether it lies beside
// the path (an obstacle's unseen side the airframe would touch) rather than on its centre line.
struct UnmappedCell {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  bool beside_path = false;
};

// Time of the first sample (every step_s) within horizon_m of path length from the start whose
// cell is unknown in `grid`, or beside which the airframe touches an unknown cell that counts
// (BesideThePath). Cells the airframe touches at the start (the start's own cell on the centre
// line) and cells outside the window do not count: the vehicle is there, seen or not. `where`,
// if given, receives that cell.
std::optional<double> firstUnknownWithin(const Trajectory& t, const VoxelGrid& grid,
                                         double horizon_m, double step_s,
                                         const BesideThePath& beside = {},
                                         UnmappedCell* where = nullptr);

// Whether the airframe on `stop`, anywhere along it, touches an unknown cell beside its centre
// line that counts (BesideThePath from vehicle_radius_m and hidden_face_m, the whole stop within
// reach): a stop that brakes along a path bending towards a mapped obstacle's unseen side is no
// clear stop, though its centre line stays in mapped space.
bool touchesHiddenFace(const Trajectory& stop, const VoxelGrid& grid, const ArbiterParams& params);

// The same rule for the committed trajectory `t` while it is flown (`elapsed_s` of it flown):
// if no plan replaced it, the vehicle would follow it for lead_s more and then brake along it.
// Returns the time (on t) of the first unknown cell within that reach - the path of lead_s plus
// knownSpaceHorizonM of the speed there - on the centre line or beside it (BesideThePath from
// vehicle_radius_m, hidden_face_m and hidden_face_reach_m), or nothing when the reach lies in
// mapped space. `where`, if given, receives that cell.
std::optional<double> firstUnknownWithinReach(const Trajectory& t, double elapsed_s, double lead_s,
                                              const VoxelGrid& grid, const ArbiterParams& params,
                                              UnmappedCell* where = nullptr);

// "at (x, y, z) on its path" or "at (x, y, z), an obstacle's unseen side beside its path".
std::string describeUnmappedCell(const UnmappedCell& cell);

// True when `answer` (starting at answer_start_utime) may be committed for `requested`;
// otherwise false with the first failed check in *why. `grid` may be null (no map yet: no
// collision checks). Its reach (firstUnknownWithinReach) is taken reach_lead_s after its start.
bool checkAnswer(const Trajectory& answer, int64_t answer_start_utime,
                 const RequestedStart& requested, const VoxelGrid* grid,
                 const ArbiterParams& params, double reach_lead_s, std::string* why);

}  // namespace mmh::arbiter
