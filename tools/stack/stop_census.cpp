#include "stop_census.hpp"

#include <algorithm>
#include <cmath>

#include "mmh/arbiter_status_t.hpp"
#include "mmh/common/decision_names.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/plan_result_t.hpp"

namespace mmh {
namespace {

bool contains(const std::string& text, const char* part) {
  return text.find(part) != std::string::npos;
}

// The arbiter's reason for rejecting a mode's answer: "<MODE> rejected: <why>; " in its text.
std::string rejectionOf(const std::string& detail, const std::string& mode) {
  const std::string key = mode + " rejected: ";
  const size_t at = detail.find(key);
  if (at == std::string::npos) return "";
  const size_t from = at + key.size();
  const size_t end = detail.find(';', from);
  return detail.substr(from, end == std::string::npos ? std::string::npos : end - from);
}

// What a verification failure or a rejection found, without its numbers, times and places, so
// that failures of one kind count together: "verification: max acceleration 2.4 m/s^2 exceeds 2
// [A* ...]" gives "max acceleration", "collides with the arbiter's map 0.31 s from its start, at
// (...)" gives "collides with the arbiter's map".
std::string failureKind(const std::string& text) {
  std::string head = text;
  const std::string prefix = "verification: ";
  if (head.compare(0, prefix.size(), prefix) == 0) head = head.substr(prefix.size());
  const size_t cut = head.find_first_of("0123456789([");
  head = head.substr(0, cut);
  while (!head.empty() && (head.back() == ' ' || head.back() == ',')) head.pop_back();
  if (head.size() > 3 && head.compare(head.size() - 3, 3, " by") == 0) head.resize(head.size() - 3);
  return head;
}

// A stop is its own decision right after the failed one that caused it (same step).
constexpr double kSameDecisionStepS = 0.011;

}  // namespace

std::map<std::string, int> FlightCensus::causeCounts() const {
  std::map<std::string, int> counts;
  for (const StopRecord& s : stops) ++counts[s.cause];
  return counts;
}

std::string stopCause(const std::string& detail) {
  // Most specific first: a deadline or stale odometry is named inside "no usable answer" texts.
  if (contains(detail, "LOCAL_MAP is stale")) return "stale map";
  if (contains(detail, "ODOMETRY is stale")) return "stale odometry";
  if (contains(detail, "no answer by the deadline")) return "deadline";
  if (contains(detail, "answer came after its start time")) return "late answer";
  if (contains(detail, "no usable answer and unmapped space")) {
    return "no usable answer + unmapped space ahead";
  }
  if (contains(detail, "no usable answer")) return "no usable answer + danger ahead";
  return "other";
}

std::string planReasonName(int reason) {
  switch (reason) {
    case plan_result_t::REASON_NONE:
      return "none";
    case plan_result_t::REASON_BAD_INPUT:
      return "bad input";
    case plan_result_t::REASON_NO_MAP:
      return "no map";
    case plan_result_t::REASON_START_IN_OBSTACLE:
      return "start in obstacle";
    case plan_result_t::REASON_TARGET_IN_OBSTACLE:
      return "target in obstacle";
    case plan_result_t::REASON_TARGET_OUT_OF_BOUNDS:
      return "target out of bounds";
    case plan_result_t::REASON_NO_PATH:
      return "no path";
    case plan_result_t::REASON_CORRIDOR:
      return "corridor";
    case plan_result_t::REASON_OPTIMIZER:
      return "optimizer";
    case plan_result_t::REASON_VERIFY:
      return "verify";
    case plan_result_t::REASON_INFEASIBLE_START:
      return "infeasible start";
    case plan_result_t::REASON_START_EQUALS_TARGET:
      return "start equals target";
    case plan_result_t::REASON_EMPTY_REFERENCE:
      return "empty reference";
  }
  return "reason " + std::to_string(reason);
}

void StopCensusBuilder::onPlanResult(int mode, bool ok, int reason, const std::string& detail) {
  if (mode < plan_request_t::MODE_FPM || mode > plan_request_t::MODE_EAM) return;
  round_.push_back(Answer{mode, ok, reason, detail});
}

std::vector<ModeFailure> StopCensusBuilder::failuresOf(const DecisionSample& decision) const {
  std::vector<ModeFailure> out;
  int answered = 0;
  for (const Answer& a : round_) {
    answered |= 1 << a.mode;
    ModeFailure f;
    f.mode = modeName(a.mode);
    if (!a.ok) {
      f.reason = planReasonName(a.reason);
      const std::string kind = failureKind(a.detail);
      if (a.reason == plan_result_t::REASON_VERIFY && !kind.empty()) f.reason += ": " + kind;
      f.text = a.detail;
    } else {
      // A verified answer that was still not committed: the arbiter says why in its text.
      const std::string why = rejectionOf(decision.detail, f.mode);
      f.reason = why.empty() ? "answer not used" : "rejected: " + failureKind(why);
      f.text = why;
    }
    out.push_back(f);
  }
  for (int mode = plan_request_t::MODE_FPM; mode <= plan_request_t::MODE_EAM; ++mode) {
    if ((decision.modes_asked & (1 << mode)) && !(answered & (1 << mode)))
      out.push_back(ModeFailure{modeName(mode), "no answer", ""});
  }
  return out;
}

void StopCensusBuilder::onDecision(const DecisionSample& d) {
  const bool follows_failure =
      last_decision_failed_ && d.time_s - last_decision_time_s_ < kSameDecisionStepS;
  // A round that kept the committed trajectory chose a way on, as a commit does.
  if (d.outcome == arbiter_status_t::OUTCOME_COMMITTED ||
      d.outcome == arbiter_status_t::OUTCOME_KEPT) {
    closeStop(d.time_s);
    calls_without_commit_ = 0;
    failed_since_commit_ = 0;
  } else {
    calls_without_commit_ += static_cast<int>(round_.size());
    census_.max_calls_without_commit =
        std::max(census_.max_calls_without_commit, calls_without_commit_);
  }
  if (d.outcome == arbiter_status_t::OUTCOME_FAILED) {
    ++failed_since_commit_;
    last_failures_ = failuresOf(d);
  }
  if (d.outcome == arbiter_status_t::OUTCOME_STOPPING) {
    closeStop(d.time_s);
    StopRecord s;
    s.time_s = d.time_s;
    s.trigger = triggerName(d.trigger);
    s.cause = stopCause(d.detail);
    s.detail = d.detail;
    if (follows_failure) s.failed_modes = last_failures_;
    s.failed_decisions_before = failed_since_commit_;
    s.lowest_speed_mps = last_speed_mps_;
    census_.stops.push_back(std::move(s));
    stop_holding_ = true;
  }
  last_decision_failed_ = d.outcome == arbiter_status_t::OUTCOME_FAILED;
  last_decision_time_s_ = d.time_s;
  round_.clear();
}

void StopCensusBuilder::noteNoProgress(double from_s, double to_s) {
  if (to_s - from_s > census_.longest_no_progress_s) {
    census_.longest_no_progress_s = to_s - from_s;
    census_.longest_no_progress_from_s = from_s;
  }
}

void StopCensusBuilder::closeStop(double time_s) {
  if (!stop_holding_) return;
  StopRecord& s = census_.stops.back();
  s.held_s = std::max(0.0, time_s - s.time_s);
  stop_holding_ = false;
}

void StopCensusBuilder::onProgress(double time_s, double distance_to_goal_m, double speed_mps) {
  last_speed_mps_ = speed_mps;
  if (stop_holding_) {
    StopRecord& s = census_.stops.back();
    s.lowest_speed_mps = std::min(s.lowest_speed_mps, speed_mps);
  }
  if (!have_progress_) {
    have_progress_ = true;
    best_distance_m_ = distance_to_goal_m;
    progress_time_s_ = time_s;
    return;
  }
  if (distance_to_goal_m < best_distance_m_ - kProgressStepM) {
    noteNoProgress(progress_time_s_, time_s);
    best_distance_m_ = distance_to_goal_m;
    progress_time_s_ = time_s;
  }
}

FlightCensus StopCensusBuilder::finish(double end_time_s) const {
  StopCensusBuilder done = *this;
  // Calls of a round still open at the end never got a commit either.
  done.calls_without_commit_ += static_cast<int>(round_.size());
  done.census_.max_calls_without_commit =
      std::max(done.census_.max_calls_without_commit, done.calls_without_commit_);
  if (have_progress_) done.noteNoProgress(progress_time_s_, end_time_s);
  done.closeStop(end_time_s);
  return done.census_;
}

}  // namespace mmh
