// How every LOCAL_MAP consumer (awareness, SOM, EAM, arbiter) applies a message and counts the
// outcome in its HEARTBEAT, under the same counter names everywhere.
#pragma once

#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/local_map_codec.hpp"

namespace mmh {

// Applies `msg` to `receiver` and counts the result in `ctx`: map_applied (with
// map_losses_bridged when messages before it were lost but it applied exactly), map_gap,
// map_waiting_for_keyframe, map_stale, or rejected_map (logged with the reason).
LocalMapReceiver::Result applyAndCount(LocalMapReceiver& receiver, const local_map_t& msg,
                                       ServiceContext& ctx);

}  // namespace mmh
