// What the arbiter observes of the computer it runs on: per mode, how long answers take from
// request to arrival (late answers included: they are the measurement that matters), over a
// sliding window of the last seconds, and how old LOCAL_MAP messages are when they arrive.
// The latency budget (replan_rules.hpp, latencyBudget) reads its percentiles, so that a loaded
// computer lengthens the replan lead and the answer deadline instead of letting answers miss them.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <map>

#include "mmh/arbiter/modes.hpp"

namespace mmh::arbiter {

class LatencyMonitor {
 public:
  // Samples older than window_s are forgotten, so that the budget returns to normal once the
  // load has gone.
  explicit LatencyMonitor(double window_s) : window_us_(static_cast<int64_t>(window_s * 1e6)) {}

  void onRequest(int64_t request_id, Mode mode, int64_t sent_utime);
  // An answer to a request seen by onRequest (others are ignored); returns its latency in
  // seconds, or a negative value when the request is unknown.
  double onAnswer(int64_t request_id, int64_t received_utime);
  void onMapAge(double age_s, int64_t now);
  // Drops the samples that left the window by `now`.
  void expire(int64_t now);

  // q-quantile (0..1) of the window, nearest rank; 0 without samples.
  double answerLatency(Mode mode, double q) const;
  // The largest q-quantile over the planning modes.
  double worstAnswerLatency(double q) const;
  double mapAge(double q) const;
  int samples(Mode mode) const;

 private:
  struct Sample {
    int64_t utime = 0;
    double value = 0.0;
  };
  void push(std::deque<Sample>& window, int64_t utime, double value);

  int64_t window_us_;
  std::array<std::deque<Sample>, 5> answers_;  // per Mode index
  std::deque<Sample> map_ages_;
  struct Pending {
    Mode mode = Mode::kNone;
    int64_t sent_utime = 0;
  };
  std::map<int64_t, Pending> pending_;  // requests not answered yet (bounded, oldest dropped)
};

}  // namespace mmh::arbiter
