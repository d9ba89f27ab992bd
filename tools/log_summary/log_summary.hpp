// Reads an LCM log of an MMH flight and condenses it: channels and rates, planning iterations
// per mode, request-to-result latency percentiles, LOCAL_MAP sequence gaps, arbiter outcomes.
#pragma once

#include <cstdint>
#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace mmh {

struct ChannelStats {
  int64_t messages = 0;
  int64_t bytes = 0;
  int64_t first_us = 0, last_us = 0;
  int64_t undecodable = 0;
  double rateHz() const;
};

struct Percentiles {
  int64_t count = 0;
  double p50 = 0, p90 = 0, p99 = 0, max = 0, mean = 0;
};
Percentiles percentiles(std::vector<double> values);

struct ModeStats {
  int64_t results = 0, ok = 0, failed = 0;
  std::vector<double> compute_ms;  // from PLAN_RESULT.compute_us
  std::vector<double> latency_ms;  // request to result, log timestamps
  std::map<int, int64_t> failure_reasons;
};

struct VehicleSummary {                          // one channel prefix
  std::map<std::string, ChannelStats> channels;  // base channel name (prefix removed)
  std::map<int, ModeStats> modes;                // plan_request_t.MODE_*
  int64_t requests = 0, unanswered_requests = 0;
  int64_t map_keyframes = 0, map_deltas = 0, map_gaps = 0, map_missing = 0;
  int64_t map_keyframe_bytes_max = 0, map_delta_bytes_max = 0;
  double map_delta_bytes_mean = 0;
  std::map<int, int64_t> outcomes;  // arbiter_status_t.OUTCOME_* -> count
  std::map<int, int64_t> commits;   // committed mode -> count
  bool mission_seen = false, reached = false, collided = false;
  double flight_time_s = 0, distance_m = 0, energy = 0;
};

struct LogSummary {
  std::string path;
  int64_t events = 0;
  int64_t first_us = 0, last_us = 0;
  std::map<std::string, VehicleSummary> vehicles;  // by prefix ("" for none)
};

// Throws std::runtime_error when the file cannot be read.
LogSummary summarizeLog(const std::string& path);
void printSummary(const LogSummary& summary, std::ostream& out);

}  // namespace mmh
