// The catalogue of bad input that every MMH service must survive: malformed, inconsistent,
// mistyped or out-of-range messages, as raw encoded buffers for their channel, each with the
// HEARTBEAT counters that must rise at the services that receive it. Used by mmh-bad-input
// against running services and by the unit test that feeds it through the runtime.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mmh::bad_input {

// A HEARTBEAT counter that must rise at a service; "msgs_rejected" is the heartbeat's total.
struct Expectation {
  std::string service;
  std::string counter;
};

struct BadMessage {
  std::string name;     // what is wrong, e.g. "ODOMETRY with a NaN position"
  std::string channel;  // base channel (without prefix)
  std::vector<uint8_t> data;
  std::vector<Expectation> expect;
  double pause_s = 0.02;  // wait after publishing (large messages take longer to handle)
};

// Which services the messages are aimed at: the planning stack (mapping, awareness, fpm, som,
// eam, arbiter; not the simulator), or the simulator alone (TRAJECTORY and GOAL).
enum class Target { kStack, kSim };

struct CatalogueOptions {
  int64_t utime0 = 0;                   // message clock of the first message (e.g. the wall clock)
  int64_t huge_scan_points = 2000000;   // points of the oversized scan
  int64_t mapping_max_points = 500000;  // the receiver's mapping.max_points (for the check)
};

std::vector<BadMessage> makeBadMessages(Target target, const CatalogueOptions& options);

// The services a target's messages reach.
std::vector<std::string> servicesOf(Target target);

}  // namespace mmh::bad_input
