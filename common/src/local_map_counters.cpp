#include "mmh/common/local_map_counters.hpp"

#include <string>

namespace mmh {

LocalMapReceiver::Result applyAndCount(LocalMapReceiver& receiver, const local_map_t& msg,
                                       ServiceContext& ctx) {
  using Result = LocalMapReceiver::Result;
  const int64_t bridged_before = receiver.lossesBridged();
  std::string reason;
  const Result result = receiver.apply(msg, &reason);
  switch (result) {
    case Result::kApplied:
      ctx.increment("map_applied");
      if (receiver.lossesBridged() > bridged_before) ctx.increment("map_losses_bridged");
      break;
    case Result::kGap:
      ctx.increment("map_gap");
      logDebug("LOCAL_MAP " + reason + ": waiting for the next keyframe");
      break;
    case Result::kWaitingForKeyframe:
      ctx.increment("map_waiting_for_keyframe");
      break;
    case Result::kStale:
      ctx.increment("map_stale");
      break;
    case Result::kAlreadyBuilt:
      ctx.increment("map_keyframes_skipped");
      break;
    case Result::kRejected:
      ctx.reject("rejected_map", "LOCAL_MAP " + std::to_string(msg.map_seq) + ": " + reason);
      break;
  }
  return result;
}

}  // namespace mmh
