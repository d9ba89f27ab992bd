// The census of a flight's stops and stalls (issue "Flow through clutter"): every stop of the
// arbiter (ARBITER_STATUS with outcome stopping) with its time, trigger, the modes that failed
// before it, a short cause, how long it held and how slow the vehicle got; the longest run of
// planning calls without a commit; the longest time without progress toward the goal. Fed
// message by message by the stack's observer, so that the tests can feed it a synthetic
// sequence.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace mmh {

// Distance to the goal has to shrink by more than this to count as progress: far above the
// path sampling's rounding, below what one 10 Hz sample covers at cruise speed.
constexpr double kProgressStepM = 0.1;

// A stop brought the vehicle to rest when its sampled speed fell to this or below.
constexpr double kRestSpeedMps = 0.1;

// What the census needs of one ARBITER_STATUS.
struct DecisionSample {
  double time_s = 0.0;  // simulated seconds since the start of the flight
  int trigger = 0;      // arbiter_status_t::TRIGGER_*
  int outcome = 0;      // arbiter_status_t::OUTCOME_*
  int modes_asked = 0;  // bit mask 1 << plan_request_t::MODE_*
  std::string detail;
};

// A mode's part in a round of planning that ended without a commit.
struct ModeFailure {
  std::string mode;  // "FPM", "SOM", "EAM"
  // Short, to count: "no path", "optimizer", "verify: max acceleration", "rejected: ...",
  // "no answer".
  std::string reason;
  std::string text;  // the planner's detail text (PLAN_RESULT), if any
};

struct StopRecord {
  double time_s = 0.0;
  std::string trigger;                    // triggerName()
  std::string cause;                      // stopCause()
  std::string detail;                     // the stop decision's own text
  std::vector<ModeFailure> failed_modes;  // of the failed decision that led to the stop, if any
  int failed_decisions_before = 0;        // failed decisions since the last commit
  // From the stop to the next decision that commits a way on (or keeps one), or to the end of
  // the flight; a stop that a mode's answer replaces within a fraction of a second only braked.
  double held_s = 0.0;
  // The vehicle's lowest speed over that time (10 Hz samples, and the last one before it).
  double lowest_speed_mps = 0.0;
  bool reachedRest() const { return lowest_speed_mps <= kRestSpeedMps; }
};

struct FlightCensus {
  std::vector<StopRecord> stops;
  // The longest run of planning calls (every mode) whose rounds all ended without a commit (or
  // a kept committed trajectory).
  int max_calls_without_commit = 0;
  // The longest stretch in which the distance to the goal did not shrink by kProgressStepM,
  // from the start of the flight to its end (arrival, collision or timeout), and its start.
  double longest_no_progress_s = 0.0;
  double longest_no_progress_from_s = 0.0;
  std::map<std::string, int> causeCounts() const;
};

// Short category of a stop from its decision text: "stale map", "stale odometry", "deadline"
// (a mode gave no answer by the deadline), "late answer", "no usable answer + danger ahead", or
// "other" for a text this census does not know.
std::string stopCause(const std::string& detail);

// Short name of a plan_result_t::REASON_* code ("no path", "corridor", ...).
std::string planReasonName(int reason);

class StopCensusBuilder {
 public:
  // Every PLAN_RESULT, in the order received (before the decision it belongs to).
  void onPlanResult(int mode, bool ok, int reason, const std::string& detail);
  void onDecision(const DecisionSample& decision);
  // The vehicle's distance to the goal and its speed, sampled along the flight.
  void onProgress(double time_s, double distance_to_goal_m, double speed_mps);
  // The census with the flight ended at end_time_s (an open stretch without progress counts).
  FlightCensus finish(double end_time_s) const;

 private:
  struct Answer {
    int mode;
    bool ok;
    int reason;
    std::string detail;
  };
  std::vector<ModeFailure> failuresOf(const DecisionSample& decision) const;
  void noteNoProgress(double from_s, double to_s);
  // Ends the stop still holding (if any) at time_s.
  void closeStop(double time_s);

  FlightCensus census_;
  std::vector<Answer> round_;  // answers since the last decision
  int calls_without_commit_ = 0;
  int failed_since_commit_ = 0;
  std::vector<ModeFailure> last_failures_;
  bool last_decision_failed_ = false;
  double last_decision_time_s_ = -1.0;
  bool have_progress_ = false;
  double best_distance_m_ = 0.0, progress_time_s_ = 0.0;
  double last_speed_mps_ = 0.0;
  bool stop_holding_ = false;  // the last stop in census_.stops has not ended yet
};

}  // namespace mmh
