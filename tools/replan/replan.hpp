// Re-plans the requests a planning mode received in a recorded flight: every PLAN_REQUEST_EAM (or
// _SOM) of an LCM log is given to this build's planner, with the map the mode had rebuilt from
// LOCAL_MAP at that moment, and paired with the answer it gave then. The desk tool for a change to
// a mode: how many of a flight's failures it turns into answers, and which answers it loses.
#pragma once

#include <cstdint>
#include <map>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "mmh/common/config.hpp"
#include "mmh/common/trajectory.hpp"

namespace mmh {

class ReplanInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One request of the log, planned again.
struct ReplanOutcome {
  double t_s = 0.0;  // log time since the first event
  int64_t request_id = 0;
  double start_speed_mps = 0.0;
  double start_acceleration_mps2 = 0.0;
  bool logged_answer = false;  // the log holds the mode's PLAN_RESULT for it
  bool logged_ok = false;
  std::string logged_detail;  // failure text of the logged answer
  bool ok = false;            // planned again
  std::string detail;         // failure text now ("" when ok)
  double compute_ms = 0.0;    // planned again, wall clock
  // The answer planned again (when ok): how far it goes and how fast.
  double target_distance_m = 0.0;  // straight from the start to the requested target
  double duration_s = 0.0;
  double length_m = 0.0;  // arc length
  double max_speed_mps = 0.0;
  double jerk_energy = 0.0;  // integral of |jerk|^2 (m^2/s^5)
};

struct ReplanOptions {
  std::string mode = "eam";  // eam or som
  std::string prefix;        // channel prefix of the vehicle
  Config config;             // planner parameters and map.inflation_m
  // EAM only: the planner's round-by-round trace of the request with this id goes to `trace`.
  int64_t trace_request_id = -1;
  std::ostream* trace = nullptr;
  // The request with this id, planned again, goes to `samples`: its start, the path the mode
  // searched, and its answer (or the trajectory the mode refused) sampled in time
  // (printTrajectorySamples).
  int64_t samples_request_id = -1;
  std::ostream* samples = nullptr;
};

// All requests of the mode in the log, in order. Throws ReplanInputError when the log cannot be
// read or the mode is unknown.
std::vector<ReplanOutcome> replanLog(const std::string& log_path, const ReplanOptions& options);

// One line per step_s of `t` (and its end): time, position, speed, acceleration and jerk, under a
// header line naming the columns.
void printTrajectorySamples(const Trajectory& t, double step_s, std::ostream& out);

struct ReplanSummary {
  int requests = 0;       // requests with a logged answer
  int unanswered = 0;     // requests without one in the log (not counted above)
  int failed_before = 0;  // logged failures
  int failed_now = 0;
  int fixed = 0;   // failed then, answered now
  int broken = 0;  // answered then, failed now
  double mean_compute_ms = 0.0;
  double max_compute_ms = 0.0;
  // The answers now: how fast they fly (their total length over their total duration) and how
  // smooth they are (mean integral of |jerk|^2), so that a change to a mode shows whether its
  // answers got slower or rougher, not only whether it answers.
  double answered_length_m = 0.0;
  double answered_duration_s = 0.0;
  double mean_speed_mps = 0.0;
  double mean_jerk_energy = 0.0;
  std::map<std::string, int> reasons_now;  // failure text without its numbers -> count
};

ReplanSummary summarize(const std::vector<ReplanOutcome>& outcomes);

// A failure's text with its numbers taken out ("max acceleration # m/s^# exceeds #"), so that
// failures of one kind count together.
std::string failureKind(const std::string& detail);

void printReplanSummary(const ReplanSummary& summary, std::ostream& out);

}  // namespace mmh
