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

struct DecisionLine {  // one ARBITER_STATUS, for --decisions
  double t_s = 0;      // log time since the first event
  int trigger = 0, outcome = 0, committed_mode = 0;
  bool safe = true;
  double x = 0, y = 0;
  std::string detail;
  double reaction_ms = -1;  // answering a newly mapped danger: its reaction time; else -1
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
  // Decisions taken with the arbiter's latency budget degraded, and the longest deadline used.
  int64_t degraded_decisions = 0;
  double max_answer_deadline_s = 0;
  // A newly mapped danger to its answer (commit or stop): the status's arrival in the log (its own
  // time when the log was not recorded in real time) minus the scan time of the map that showed it.
  std::vector<double> reaction_ms;
  std::vector<DecisionLine> decisions;
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
// Every arbiter decision, one per line.
void printDecisions(const LogSummary& summary, std::ostream& out);

// What tools/plot_flight.py draws, as JSON: the flown path (from ODOMETRY, 10 Hz, with speed
// and the mode of the trajectory being flown), every committed decision (position, mode), the
// goal, the mission result, and the xy footprint of every cell the vehicle mapped as occupied.
// `prefix` selects the vehicle. Throws std::runtime_error when the log cannot be read.
void exportFlight(const std::string& log_path, const std::string& prefix, std::ostream& out);

}  // namespace mmh
