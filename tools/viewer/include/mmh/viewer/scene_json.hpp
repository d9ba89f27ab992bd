// JSON encoding of what the viewer sends: one function per kind of scene message. Positions are
// rounded to the millimetre and times given in seconds of the message clock, so the messages stay
// small; field names are those of the channel schemas (channel_schemas.hpp).
#pragma once

#include <nlohmann/json.hpp>

#include "mmh/arbiter_status_t.hpp"
#include "mmh/awareness_t.hpp"
#include "mmh/heartbeat_t.hpp"
#include "mmh/mission_status_t.hpp"
#include "mmh/odometry_t.hpp"
#include "mmh/plan_debug_t.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/plan_result_t.hpp"
#include "mmh/trajectory_t.hpp"
#include "mmh/viewer/flown_path.hpp"
#include "mmh/viewer/voxel_layer.hpp"

namespace mmh::viewer {

double roundTo(double value, double step);
nlohmann::json vec3Json(const double v[3], double step = 1e-3);

nlohmann::json odometryJson(const odometry_t& msg);
// The committed trajectory sampled every sample_s seconds (flattened x, y, z), with its mode.
nlohmann::json trajectoryJson(const trajectory_t& msg, double sample_s);
nlohmann::json awarenessJson(const awareness_t& msg);
nlohmann::json planRequestJson(const plan_request_t& msg);
nlohmann::json planResultJson(const plan_result_t& msg);
nlohmann::json decisionJson(const arbiter_status_t& msg);
nlohmann::json heartbeatJson(const heartbeat_t& msg);
nlohmann::json missionJson(const mission_status_t& msg);
// snapshot: the changes are the whole layer (a client that connected late), not a delta.
nlohmann::json voxelsJson(const VoxelChanges& changes, double resolution_m, bool snapshot);
nlohmann::json pathJson(const std::vector<PathSample>& samples, bool snapshot);
// PLAN_DEBUG with each corridor polytope as its vertices (flattened x, y, z), ready to draw.
nlohmann::json planDebugJson(const plan_debug_t& msg);

// Where `mmh-viewer --log` is in the recorded flight. generation counts the jumps (seeks): a
// client that sees it change drops its scene, and the snapshots of the new time follow, then
// the same state with ready (false only on the first message of a jump).
struct PlaybackState {
  int64_t start_utime = 0, end_utime = 0, now_utime = 0;
  bool playing = false;
  double speed = 1.0;
  int64_t generation = 0;
  bool ready = true;
};
nlohmann::json playbackJson(const PlaybackState& state);

}  // namespace mmh::viewer
