// Checks of every decoded MMH message: finite numbers, sizes that agree with the data, values in
// range. Each returns false with a short reason; the runtime counts and logs the rejection.
#pragma once

#include <string>

#include "mmh/arbiter_status_t.hpp"
#include "mmh/awareness_t.hpp"
#include "mmh/goal_t.hpp"
#include "mmh/heartbeat_t.hpp"
#include "mmh/local_map_t.hpp"
#include "mmh/mission_status_t.hpp"
#include "mmh/odometry_t.hpp"
#include "mmh/plan_debug_t.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/plan_result_t.hpp"
#include "mmh/pointcloud_t.hpp"
#include "mmh/setpoint_t.hpp"
#include "mmh/trajectory_t.hpp"

namespace mmh {

// Upper bounds that no legitimate message reaches.
constexpr int32_t kMaxTrajectoryPieces = 4096;
constexpr int32_t kMaxPointcloudCoords = 3 * 4'000'000;
constexpr int32_t kMaxWaypoints = 1024;
constexpr int32_t kMaxHeartbeatCounters = 256;
constexpr int32_t kMaxDebugValues = 1'000'000;  // plan_debug_t: values per array
constexpr double kMaxAbsCoordinate_m = 1e6;
constexpr size_t kMaxTextLength = 4096;  // free-text fields (detail, state_detail)
// No trajectory of this system lasts an hour; checking a longer one would take the arbiter minutes.
constexpr double kMaxTrajectoryDuration_s = 3600.0;
// Message-clock times beyond this (about the year 5100, in microseconds since 1970) are absurd: one
// such message would move a receiver's clock so far ahead that every input looked stale forever.
constexpr int64_t kMaxUtime_us = int64_t{100'000'000} * 1'000'000'000;

bool validate(const header_t& msg, std::string* why);
bool validate(const odometry_t& msg, std::string* why);
bool validate(const pointcloud_t& msg, std::string* why);  // NaN points are filtered, not rejected
bool validate(const goal_t& msg, std::string* why);
bool validate(const local_map_t& msg, std::string* why);
bool validate(const awareness_t& msg, std::string* why);
bool validate(const trajectory_t& msg, std::string* why);
bool validate(const plan_request_t& msg, std::string* why);
bool validate(const plan_result_t& msg, std::string* why);
bool validate(const arbiter_status_t& msg, std::string* why);
bool validate(const heartbeat_t& msg, std::string* why);
bool validate(const mission_status_t& msg, std::string* why);
bool validate(const setpoint_t& msg, std::string* why);
bool validate(const plan_debug_t& msg, std::string* why);

}  // namespace mmh
