// Replays a recorded flight's inputs (GOAL, ODOMETRY, POINTCLOUD of one channel prefix) into the
// planner services hosted in lock-step (PlannerHost) and collects the recorded and the replayed
// arbiter decisions (ARBITER_STATUS) for comparison.
#pragma once

#include <cstdint>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "decision.hpp"
#include "mmh/common/config.hpp"

namespace mmh {

// The log cannot be replayed as asked (unreadable, no inputs, ambiguous prefix): a usage error.
class ReplayInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ReplayOptions {
  std::string log_path;
  Config config;
  std::string policy;  // empty: arbiter.policy of the config
  std::string prefix;  // empty with auto_prefix: the only prefix with ODOMETRY in the log
  bool auto_prefix = true;
};

struct ReplayResult {
  std::string prefix;
  int64_t events = 0;  // every event of the log
  int64_t goals = 0, odometry = 0, pointclouds = 0, undecodable = 0;
  int64_t steps = 0;      // input batches (same message time) each followed by a drain
  double flight_s = 0.0;  // message time from the first to the last input
  double wall_s = 0.0;    // time the replay took
  std::vector<Decision> recorded, replayed;
};

// Channel prefixes that have ODOMETRY in the log (throws ReplayInputError if unreadable).
std::set<std::string> inputPrefixes(const std::string& log_path);

ReplayResult replayLog(const ReplayOptions& options);

}  // namespace mmh
