// The viewer's channels: what the page and Foxglove clients subscribe to.
#pragma once

namespace mmh::viewer::topics {
inline constexpr const char* kMapVoxels = "/mmh/map_voxels";   // occupied voxels added/removed
inline constexpr const char* kOdometry = "/mmh/odometry";      // vehicle state, decimated
inline constexpr const char* kFlownPath = "/mmh/flown_path";   // new path samples
inline constexpr const char* kTrajectory = "/mmh/trajectory";  // each committed trajectory
inline constexpr const char* kAwareness = "/mmh/awareness";    // the sensing ray and verdict
inline constexpr const char* kPlanRequest = "/mmh/plan_request";
inline constexpr const char* kPlanResult = "/mmh/plan_result";
inline constexpr const char* kDecision = "/mmh/decision";  // one per ARBITER_STATUS
inline constexpr const char* kHeartbeat = "/mmh/heartbeat";
inline constexpr const char* kMission = "/mmh/mission";
inline constexpr const char* kPlanDebug = "/mmh/plan_debug";  // corridor, A* paths, {p, v} pairs
inline constexpr const char* kPlayback = "/mmh/playback";     // --log only: the time slider
}  // namespace mmh::viewer::topics
