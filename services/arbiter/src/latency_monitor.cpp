#include "mmh/arbiter/latency_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mmh::arbiter {
namespace {

// Requests without an answer are forgotten after this many newer ones (a dead mode never
// answers; its requests must not pile up); a window holds at most kMaxSamples.
constexpr size_t kMaxPending = 256;
constexpr size_t kMaxSamples = 1000;

template <class Window>
double quantile(const Window& values, double q) {
  if (values.empty()) return 0.0;
  std::vector<double> sorted;
  sorted.reserve(values.size());
  for (const auto& s : values) sorted.push_back(s.value);
  std::sort(sorted.begin(), sorted.end());
  const double rank = std::ceil(std::clamp(q, 0.0, 1.0) * static_cast<double>(sorted.size()));
  const size_t index = static_cast<size_t>(std::max(1.0, rank)) - 1;
  return sorted[std::min(index, sorted.size() - 1)];
}

}  // namespace

void LatencyMonitor::onRequest(int64_t request_id, Mode mode, int64_t sent_utime) {
  pending_[request_id] = Pending{mode, sent_utime};
  while (pending_.size() > kMaxPending) pending_.erase(pending_.begin());
}

double LatencyMonitor::onAnswer(int64_t request_id, int64_t received_utime) {
  const auto it = pending_.find(request_id);
  if (it == pending_.end()) return -1.0;
  const double latency_s = std::max(0.0, (received_utime - it->second.sent_utime) * 1e-6);
  push(answers_[modeIndex(it->second.mode)], received_utime, latency_s);
  pending_.erase(it);
  return latency_s;
}

void LatencyMonitor::onMapAge(double age_s, int64_t now) {
  if (std::isfinite(age_s)) push(map_ages_, now, std::max(0.0, age_s));
}

void LatencyMonitor::expire(int64_t now) {
  auto drop = [&](std::deque<Sample>& window) {
    while (!window.empty() && window.front().utime < now - window_us_) window.pop_front();
  };
  for (auto& window : answers_) drop(window);
  drop(map_ages_);
}

double LatencyMonitor::answerLatency(Mode mode, double q) const {
  return quantile(answers_[modeIndex(mode)], q);
}

double LatencyMonitor::worstAnswerLatency(double q) const {
  double worst = 0.0;
  for (Mode m : {Mode::kFpm, Mode::kSom, Mode::kEam}) worst = std::max(worst, answerLatency(m, q));
  return worst;
}

double LatencyMonitor::mapAge(double q) const {
  return quantile(map_ages_, q);
}

int LatencyMonitor::samples(Mode mode) const {
  return static_cast<int>(answers_[modeIndex(mode)].size());
}

void LatencyMonitor::push(std::deque<Sample>& window, int64_t utime, double value) {
  window.push_back(Sample{utime, value});
  while (window.size() > kMaxSamples) window.pop_front();
}

}  // namespace mmh::arbiter
