// mmh-bad-input: publishes the catalogue of bad input (bad_messages.hpp) at running services and
// checks, from their HEARTBEATs, that every one of them survived (still beating, same pid) and
// counted what it was sent. Exit code 0 when all did, 1 otherwise, 2 on bad usage.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <map>
#include <string>
#include <thread>

#include "bad_messages.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/node_options.hpp"
#include "mmh/heartbeat_t.hpp"

namespace {

using mmh::bad_input::BadMessage;
using mmh::bad_input::Expectation;

// The newest HEARTBEAT of every service (by service name) and when it arrived.
class HeartbeatWatch {
 public:
  void onHeartbeat(const mmh::heartbeat_t& msg) {
    latest_[msg.service] = msg;
    arrived_us_[msg.service] = mmh::wallTimeUs();
  }
  bool has(const std::string& service) const { return latest_.count(service) > 0; }
  const mmh::heartbeat_t& latest(const std::string& service) const { return latest_.at(service); }
  int64_t arrivedUs(const std::string& service) const { return arrived_us_.at(service); }
  const std::map<std::string, mmh::heartbeat_t>& all() const { return latest_; }

 private:
  std::map<std::string, mmh::heartbeat_t> latest_;
  std::map<std::string, int64_t> arrived_us_;
};

int64_t counterOf(const mmh::heartbeat_t& hb, const std::string& name) {
  if (name == "msgs_rejected") return hb.msgs_rejected;
  for (size_t i = 0; i < hb.counter_names.size() && i < hb.counter_values.size(); ++i) {
    if (hb.counter_names[i] == name) return hb.counter_values[i];
  }
  return 0;
}

void handleFor(lcm::LCM& lcm, double seconds) {
  const int64_t until = mmh::wallTimeUs() + static_cast<int64_t>(seconds * 1e6);
  while (mmh::wallTimeUs() < until && !mmh::stopRequested()) {
    const int64_t left_ms = (until - mmh::wallTimeUs()) / 1000;
    lcm.handleTimeout(static_cast<int>(std::clamp<int64_t>(left_ms, 1, 50)));
  }
}

}  // namespace

int main(int argc, char** argv) {
  mmh::NodeOptions node;
  std::string target_name = "stack";
  int huge_points = 2000000, mapping_max_points = 500000;
  double wait_s = 15.0, settle_s = 8.0;
  bool list = false;
  mmh::ArgParser parser("mmh-bad-input",
                        "Publishes malformed, mistyped and out-of-range messages at running "
                        "services and checks from HEARTBEAT that they survived and counted them.");
  mmh::addNodeOptions(parser, &node);
  parser.addString("--target", &target_name,
                   "stack (mapping, awareness, fpm, som, eam, arbiter) or sim (mmh-sim alone)");
  parser.addInt("--huge-scan-points", &huge_points, "points of the oversized scan (0: none)");
  parser.addInt("--mapping-max-points", &mapping_max_points,
                "the services' mapping.max_points (the oversized scan must exceed it)");
  parser.addDouble("--wait-s", &wait_s, "wait this long for every service's first HEARTBEAT");
  parser.addDouble("--settle-s", &settle_s, "wait at most this long for the counters to rise");
  parser.addFlag("--list", &list, "print the catalogue and exit");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  if (target_name != "stack" && target_name != "sim") {
    std::cerr << "mmh-bad-input: --target must be stack or sim\n";
    return 2;
  }
  const auto target =
      target_name == "sim" ? mmh::bad_input::Target::kSim : mmh::bad_input::Target::kStack;
  mmh::bad_input::CatalogueOptions catalogue;
  catalogue.utime0 = mmh::wallTimeUs();
  catalogue.huge_scan_points = huge_points;
  catalogue.mapping_max_points = mapping_max_points;
  const std::vector<BadMessage> messages = mmh::bad_input::makeBadMessages(target, catalogue);
  const std::vector<std::string> services = mmh::bad_input::servicesOf(target);
  if (list) {
    for (const BadMessage& m : messages) {
      std::cout << m.channel << ": " << m.name << " (" << m.data.size() << " bytes)\n";
    }
    return 0;
  }
  mmh::setLogServiceName("mmh-bad-input");
  try {
    auto lcm = mmh::openLcm(node.lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-bad-input", node.prefix);
    HeartbeatWatch watch;
    ctx.subscribe(mmh::channels::kHeartbeat, &HeartbeatWatch::onHeartbeat, &watch);
    mmh::installStopHandlers();

    // 1. Every service is there.
    const int64_t give_up = mmh::wallTimeUs() + static_cast<int64_t>(wait_s * 1e6);
    auto allPresent = [&] {
      return std::all_of(services.begin(), services.end(),
                         [&](const std::string& s) { return watch.has(s); });
    };
    while (!allPresent() && mmh::wallTimeUs() < give_up && !mmh::stopRequested()) {
      handleFor(*lcm, 0.1);
    }
    for (const std::string& s : services) {
      if (!watch.has(s)) {
        std::cerr << "mmh-bad-input: no HEARTBEAT from " << s << " within " << wait_s << " s\n";
        return 1;
      }
    }
    const std::map<std::string, mmh::heartbeat_t> baseline = watch.all();

    // 2. Publish the catalogue.
    std::map<std::pair<std::string, std::string>, int> expected;
    for (const BadMessage& m : messages) {
      for (const Expectation& e : m.expect) ++expected[{e.service, e.counter}];
      const std::string channel = ctx.channel(m.channel);
      if (lcm->publish(channel, m.data.data(), static_cast<unsigned>(m.data.size())) != 0) {
        std::cerr << "mmh-bad-input: publishing on " << channel << " failed\n";
        return 1;
      }
      handleFor(*lcm, m.pause_s);
    }
    const int64_t published_us = mmh::wallTimeUs();

    // 3. Wait until every counter rose and every service beat again after the last message.
    auto rise = [&](const std::string& service, const std::string& counter) {
      return counterOf(watch.latest(service), counter) - counterOf(baseline.at(service), counter);
    };
    auto satisfied = [&] {
      for (const auto& [key, n] : expected) {
        if (rise(key.first, key.second) < n) return false;
      }
      for (const std::string& s : services) {
        if (watch.arrivedUs(s) <= published_us) return false;
      }
      return true;
    };
    const int64_t settle_until = mmh::wallTimeUs() + static_cast<int64_t>(settle_s * 1e6);
    while (!satisfied() && mmh::wallTimeUs() < settle_until && !mmh::stopRequested()) {
      handleFor(*lcm, 0.1);
    }

    // 4. Report.
    bool ok = true;
    for (const BadMessage& m : messages) {
      std::cout << m.channel << ": " << m.name << "\n";
      for (const Expectation& e : m.expect) {
        const int n = expected[{e.service, e.counter}];
        const int64_t r = rise(e.service, e.counter);
        const bool good = r >= n;
        ok = ok && good;
        std::cout << "    " << (good ? "ok      " : "MISSING ") << e.service << " " << e.counter
                  << " +" << r << " (expected +" << n << " over the whole catalogue)\n";
      }
    }
    for (const std::string& s : services) {
      const mmh::heartbeat_t& now = watch.latest(s);
      const bool alive = watch.arrivedUs(s) > published_us && now.pid == baseline.at(s).pid &&
                         now.state != mmh::heartbeat_t::STATE_STOPPING;
      ok = ok && alive;
      std::cout << (alive ? "alive   " : "DEAD    ") << s << " pid " << now.pid << ", rejected "
                << baseline.at(s).msgs_rejected << " -> " << now.msgs_rejected << "\n";
    }
    std::cout << (ok ? "PASS" : "FAIL") << ": " << messages.size() << " bad messages, "
              << services.size() << " services\n";
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "mmh-bad-input: " << e.what() << "\n";
    return 1;
  }
}
