// Braking trajectory: from a moving state to rest along the direction of motion with
// |acceleration| <= a_max (checked exactly). What the arbiter commits when no mode gave a usable
// answer and danger is ahead, or when its inputs go stale, and what mmh-setpoint brakes along when
// its watchdog trips.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "mmh/common/geofence.hpp"
#include "mmh/common/trajectory.hpp"
#include "mmh/common/voxel_grid.hpp"

namespace mmh {

// The straight stop: the start's acceleration fades out within 0.2 s while braking builds up, then
// it brakes straight ahead at nearly a_max (as makeStoppingTrajectory along a path, below).
Trajectory makeStoppingTrajectory(const KinematicState& start, double max_acc_mps2,
                                  double max_vel_mps);

// Brakes along the path of `path` from its time t0: the same curve, re-timed (so an avoidance
// manoeuvre under way is kept) to brake as hard as a_max leaves after the curve's own
// acceleration, built up and faded within 0.2 s - nearly the bang-bang stop on a straight path -
// fitted with minimum-jerk pieces through points of the re-timed curve. Starts exactly in path's
// state at t0 and ends at rest; |a| <= a_max checked exactly.
Trajectory makeStoppingTrajectory(const Trajectory& path, double t0, double max_acc_mps2,
                                  double max_vel_mps);

// Below this share of the top speed a slowdown is not made (makeSlowdownTrajectory).
constexpr double kMinSlowdownRatio = 0.1;
// Nor one that would take longer than this (s).
constexpr double kLongestSlowdownS = 60.0;

// Slows down along the path of `path` from its time t0 so that, after a smooth transition, no
// point of the rest of the path is flown faster than max_speed_mps: the same curve, re-timed by a
// factor that falls smoothly from 1 to max_speed_mps / (path's top speed after t0), fitted with
// minimum-jerk pieces; it ends where the path ends, at rest. What the arbiter commits when the
// speed it allows falls below the committed trajectory's (answers come late). Empty when the
// path is already slow enough (its top speed after t0 within max_speed_mps x (1 + tolerance)),
// too short to slow down on, or max_speed_mps is below kMinSlowdownRatio of that top speed or the
// slowed rest would last longer than kLongestSlowdownS (then stop instead).
Trajectory makeSlowdownTrajectory(const Trajectory& path, double t0, double max_speed_mps,
                                  double max_acc_mps2, double tolerance = 0.0);

// What a stop would meet: its least distance to the occupied cells' centres (at most the limit
// asked) and how far it runs through cells the map does not know.
struct StopAssessment {
  double clearance_m = 0.0;
  double unknown_m = 0.0;
};
StopAssessment assessStop(const VoxelGrid& grid, const Trajectory& stop, double limit_m);

// Whether stop `a` is safer than stop `b`: one that brings the airframe into an occupied cell
// (clearance below touch_m) is worst; between two that do not, the one through less unknown
// space (where any obstacle may stand) wins, then the one with more clearance.
bool saferStop(const StopAssessment& a, const StopAssessment& b, double touch_m);

// Stops that swerve: from `start` to rest at points beside the straight stop's end (left and
// right in the horizontal plane, 0.2 to 1 m aside), the straight stop's three minimum-jerk pieces
// with their junctions moved smoothly aside, the shortest within a_max and max_vel_mps; ordered
// from the least swerve to the most. Empty when the start is nearly at rest.
std::vector<Trajectory> makeSwervingStops(const KinematicState& start, double max_acc_mps2,
                                          double max_vel_mps);
// The first of those stops, in the same order, that `accept` takes; built one by one, so that a
// clear one found early costs little.
std::optional<Trajectory> firstSwervingStop(const KinematicState& start, double max_acc_mps2,
                                            double max_vel_mps,
                                            const std::function<bool(const Trajectory&)>& accept);

// A caller's further condition on a clear stop (the arbiter's: no mapped obstacle's unseen side
// beside it); empty: none.
using StopCondition = std::function<bool(const Trajectory&)>;

// Whether a stop keeps clearance_m from the occupied cells' centres of `grid`, runs through known
// space only (a few centimetres of unknown excepted), passes firstCollisionTime on the grid's
// inflated cells (the arbiter's check of the committed trajectory), meets also_clear and, given a
// fence, stays inside it.
bool isClearStop(const VoxelGrid& grid, const Trajectory& stop, double clearance_m,
                 const Geofence* fence = nullptr, const StopCondition& also_clear = {});

// The stop to commit when `path` is to be left at t0 (danger ahead on it): braking along it, so
// that an avoidance under way is kept, if that stays clear (isClearStop); but the straight stop
// from the same state if that is as clear and the one along the path runs much farther (a bend
// flown near a_max leaves little to brake with). When neither is clear, the first clear stop that
// swerves (firstSwervingStop), if may_swerve; else the safer (saferStop) of the two that brake,
// unless that one brings the airframe within touch_m of an occupied cell and a swerve inside the
// fence does not: then the safest of those swerves (saferStop), though it is not clear.
// Braking along a path that bends into the obstacle it is stopped for can reach it; the straight
// stop can run into unknown space that the path never crossed; a newly mapped obstacle may stand on
// both. Given a fence, a stop that leaves it is not clear, and of two braking stops that are not,
// the one that stays inside it is taken unless it touches an obstacle. A clear stop also meets
// also_clear. Without a grid, braking along the path.
Trajectory chooseStoppingTrajectory(const VoxelGrid* grid, const Trajectory& path, double t0,
                                    double max_acc_mps2, double max_vel_mps, double clearance_m,
                                    double touch_m, bool may_swerve = true,
                                    const Geofence* fence = nullptr,
                                    const StopCondition& also_clear = {});

// Least distance of the trajectory to the occupied cells' centres (sampled 1 cm apart at most),
// at most limit_m.
double minOccupiedDistance(const VoxelGrid& grid, const Trajectory& traj, double limit_m);

}  // namespace mmh
