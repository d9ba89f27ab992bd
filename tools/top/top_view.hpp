// State behind mmh-top: the latest HEARTBEAT of every service and the latest ARBITER_STATUS of
// every vehicle, with message rates, rendered as a plain-text table.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "mmh/arbiter_status_t.hpp"
#include "mmh/heartbeat_t.hpp"

namespace mmh {

class TopView {
 public:
  // now_us: the receiver's wall clock (only used for ages and rates on this screen).
  void onHeartbeat(const heartbeat_t& msg, const std::string& channel, int64_t now_us);
  void onArbiterStatus(const arbiter_status_t& msg, const std::string& channel, int64_t now_us);
  std::string render(int64_t now_us) const;
  size_t numServices() const { return services_.size(); }

 private:
  struct ServiceRow {
    std::string prefix;
    heartbeat_t last{};
    int64_t seen_us = 0;
    double in_rate = 0, out_rate = 0;
  };
  struct VehicleRow {
    arbiter_status_t last{};
    int64_t seen_us = 0;
    std::map<int, int64_t> outcomes;
    int64_t last_compute_us[4] = {0, 0, 0, 0};
  };
  std::map<std::string, ServiceRow> services_;  // key: prefix|service|host|pid
  std::map<std::string, VehicleRow> vehicles_;  // key: prefix
};

// "UAV1_HEARTBEAT" with base "HEARTBEAT" -> "UAV1_".
std::string channelPrefix(const std::string& channel, const std::string& base);

}  // namespace mmh
