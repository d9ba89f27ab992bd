#include "top_view.hpp"

#include <cstdio>
#include <sstream>

#include "mmh/common/decision_names.hpp"

namespace mmh {

std::string channelPrefix(const std::string& channel, const std::string& base) {
  if (channel.size() >= base.size() &&
      channel.compare(channel.size() - base.size(), base.size(), base) == 0)
    return channel.substr(0, channel.size() - base.size());
  return channel;
}

void TopView::onHeartbeat(const heartbeat_t& msg, const std::string& channel, int64_t now_us) {
  const std::string prefix = channelPrefix(channel, "HEARTBEAT");
  const std::string key =
      prefix + "|" + msg.service + "|" + msg.host + "|" + std::to_string(msg.pid);
  ServiceRow& row = services_[key];
  if (row.seen_us > 0 && now_us > row.seen_us) {
    const double dt = (now_us - row.seen_us) * 1e-6;
    row.in_rate = (msg.msgs_in - row.last.msgs_in) / dt;
    row.out_rate = (msg.msgs_out - row.last.msgs_out) / dt;
  }
  row.prefix = prefix;
  row.last = msg;
  row.seen_us = now_us;
}

void TopView::onArbiterStatus(const arbiter_status_t& msg, const std::string& channel,
                              int64_t now_us) {
  VehicleRow& v = vehicles_[channelPrefix(channel, "ARBITER_STATUS")];
  v.last = msg;
  v.seen_us = now_us;
  ++v.outcomes[msg.outcome];
  if (msg.compute_us_fpm) v.last_compute_us[1] = msg.compute_us_fpm;
  if (msg.compute_us_som) v.last_compute_us[2] = msg.compute_us_som;
  if (msg.compute_us_eam) v.last_compute_us[3] = msg.compute_us_eam;
}

std::string TopView::render(int64_t now_us) const {
  std::ostringstream out;
  char line[512];
  std::snprintf(line, sizeof(line), "%-8s %-14s %-12s %7s %-9s %5s %8s %8s %6s  %s\n", "PREFIX",
                "SERVICE", "HOST", "PID", "STATE", "AGE_S", "IN/S", "OUT/S", "REJ", "DETAIL");
  out << line;
  for (const auto& [key, r] : services_) {
    const double age = (now_us - r.seen_us) * 1e-6;
    std::string detail = r.last.state_detail;
    // Rejection counters are what an operator needs to see first.
    for (int i = 0; i < r.last.num_counters; ++i) {
      if (r.last.counter_names[i].rfind("rejected", 0) == 0 && r.last.counter_values[i] > 0)
        detail += " " + r.last.counter_names[i] + "=" + std::to_string(r.last.counter_values[i]);
    }
    std::snprintf(line, sizeof(line), "%-8s %-14s %-12s %7d %-9s %5.1f %8.1f %8.1f %6lld  %s\n",
                  r.prefix.empty() ? "-" : r.prefix.c_str(), r.last.service.c_str(),
                  r.last.host.c_str(), r.last.pid,
                  age > 3.0 ? "SILENT" : heartbeatStateName(r.last.state), age, r.in_rate,
                  r.out_rate, static_cast<long long>(r.last.msgs_rejected), detail.c_str());
    out << line;
  }
  for (const auto& [prefix, v] : vehicles_) {
    const arbiter_status_t& s = v.last;
    std::snprintf(line, sizeof(line),
                  "\narbiter %s: iterations FPM %d  SOM %d  EAM %d  failures %d | last compute "
                  "FPM %.2f ms  SOM %.2f ms  EAM %.2f ms\n",
                  prefix.empty() ? "-" : prefix.c_str(), s.iterations_fpm, s.iterations_som,
                  s.iterations_eam, s.failures, v.last_compute_us[1] * 1e-3,
                  v.last_compute_us[2] * 1e-3, v.last_compute_us[3] * 1e-3);
    out << line;
    std::snprintf(
        line, sizeof(line),
        "  last decision #%lld: %s -> %s %s (S=%s) at (%.1f, %.1f, %.1f), %.1f s ago: %s\n",
        static_cast<long long>(s.decision_seq), triggerName(s.trigger), outcomeName(s.outcome),
        modeName(s.committed_mode), s.awareness_safe ? "true" : "false", s.position[0],
        s.position[1], s.position[2], (now_us - v.seen_us) * 1e-6, s.detail.substr(0, 80).c_str());
    out << line;
  }
  if (services_.empty()) out << "(no HEARTBEAT received yet)\n";
  return out.str();
}

}  // namespace mmh
