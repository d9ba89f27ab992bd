// What a service does with a message once decodeChecked() accepted it, limited to the shared code
// of common/: the fuzz targets call consume() so that a valid-looking but hostile message also
// exercises LOCAL_MAP reconstruction, trajectory conversion and evaluation, and re-encoding.
// Every function aborts (a fuzzer crash) when an invariant of the accepted message breaks.
#pragma once

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

namespace mmh::fuzz {

void consume(const odometry_t& msg);
void consume(const pointcloud_t& msg);
void consume(const goal_t& msg);
void consume(const local_map_t& msg);
void consume(const awareness_t& msg);
void consume(const trajectory_t& msg);
void consume(const plan_request_t& msg);
void consume(const plan_result_t& msg);
void consume(const arbiter_status_t& msg);
void consume(const heartbeat_t& msg);
void consume(const mission_status_t& msg);
void consume(const setpoint_t& msg);
void consume(const plan_debug_t& msg);

}  // namespace mmh::fuzz
