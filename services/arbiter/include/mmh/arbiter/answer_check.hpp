// The arbiter's own check of a mode's answer before it may be committed: it trusts no mode. An
// answer must take over the committed trajectory without a jump at the requested start, keep
// the limits, stay in the geofence and collide with nothing in the arbiter's map (a start inside
// the check margin may leave it, outwards and near the start only).
#pragma once

#include <string>

#include "mmh/arbiter/arbiter_params.hpp"
#include "mmh/common/trajectory.hpp"
#include "mmh/common/voxel_grid.hpp"

namespace mmh::arbiter {

// What was asked: the answer must start at start_utime in exactly this state.
struct RequestedStart {
  int64_t start_utime = 0;
  KinematicState state;
};

// True when `answer` (starting at answer_start_utime) may be committed for `requested`;
// otherwise false with the first failed check in *why. `grid` may be null (no map yet: no
// collision checks).
bool checkAnswer(const Trajectory& answer, int64_t answer_start_utime,
                 const RequestedStart& requested, const VoxelGrid* grid,
                 const ArbiterParams& params, std::string* why);

}  // namespace mmh::arbiter
