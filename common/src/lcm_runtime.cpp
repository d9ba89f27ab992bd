#include "mmh/common/lcm_runtime.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <functional>
#include <sstream>

namespace mmh {
namespace {

std::atomic<bool> g_stop{false};

void onSignal(int) {
  g_stop.store(true);
}

std::string hostName() {
  char buf[256] = {0};
  if (gethostname(buf, sizeof(buf) - 1) != 0) return "unknown";
  return buf;
}

}  // namespace

int64_t wallTimeUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

void installStopHandlers() {
  struct sigaction sa {};
  sa.sa_handler = onSignal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

bool stopRequested() {
  return g_stop.load();
}

std::unique_ptr<lcm::LCM> openLcm(const std::string& url) {
  std::string effective = url;
  if (effective.empty()) {
    const char* env = std::getenv("LCM_DEFAULT_URL");
    effective = env ? env : "";
  }
  auto lcm = std::make_unique<lcm::LCM>(effective);
  const std::string shown =
      effective.empty() ? "udpm://239.255.76.67:7667?ttl=0 (default)" : effective;
  // LCM 1.3.1: without a multicast route good() is false; a failed self-test leaves good() true
  // but getFileno() -1. Both mean the node would be deaf.
  if (!lcm->good() || lcm->getFileno() < 0) {
    throw LcmError(
        "LCM is not usable with URL " + shown +
        ". For udpm:// this usually means there is no multicast route: on a single machine run\n"
        "  sudo ip route add 224.0.0.0/4 dev lo\n"
        "(or on the network interface that joins your machines, see "
        "docs/operations.md#several-machines),"
        " or pick another URL with --lcm-url / LCM_DEFAULT_URL.");
  }
  return lcm;
}

ServiceContext::ServiceContext(lcm::LCM& lcm, std::string service, std::string prefix)
    : lcm_(lcm),
      service_(std::move(service)),
      prefix_(std::move(prefix)),
      host_(hostName()),
      started_wall_us_(wallTimeUs()) {
  applyLossFromEnvironment();
}

void ServiceContext::applyLossFromEnvironment() {
  const char* env = std::getenv("MMH_TEST_INCOMING_LOSS");
  if (!env || !*env) return;
  std::stringstream list(env);
  std::string item;
  // A seed per service, so that receivers lose different messages.
  const uint64_t seed = std::hash<std::string>{}(service_) ^ static_cast<uint64_t>(getpid());
  while (std::getline(list, item, ',')) {
    const size_t eq = item.find('=');
    double fraction = -1.0;
    if (eq != std::string::npos) {
      const char* text = item.c_str() + eq + 1;
      char* end = nullptr;
      fraction = std::strtod(text, &end);
      if (end == text || *end != '\0') fraction = -1.0;
    }
    if (!(fraction >= 0.0 && fraction <= 1.0)) {
      logWarn(service_ + ": ignoring MMH_TEST_INCOMING_LOSS item '" + item +
              "' (expected CHANNEL=FRACTION in [0, 1])");
      continue;
    }
    const std::string base = item.substr(0, eq);
    setIncomingLoss(base, fraction, seed);
    logWarn(service_ + ": TEST SWITCH MMH_TEST_INCOMING_LOSS: dropping " +
            std::to_string(fraction) + " of the messages on " + channel(base));
  }
}

ServiceContext::~ServiceContext() {
  for (lcm::Subscription* s : lcm_subscriptions_) lcm_.unsubscribe(s);
}

int64_t ServiceContext::counter(const std::string& name) const {
  auto it = counters_.find(name);
  return it == counters_.end() ? 0 : it->second;
}

void ServiceContext::reject(const std::string& counter, const std::string& reason) {
  ++counters_[counter];
  ++msgs_rejected_;
  LogLimiter& limiter = limiters_[counter];
  if (limiter.shouldLog()) {
    logWarn(service_ + ": " + reason + " [" + counter + " = " + std::to_string(counters_[counter]) +
            "]");
  }
}

void MessageClock::observe(int64_t utime) {
  if (utime <= now_) return;
  now_ = utime;
  moved_wall_us_ = wallTimeUs();
}

int64_t ServiceContext::estimatedNow(int64_t wall_now_us) const {
  if (clock_.now() == 0) return 0;
  return clock_.now() + std::max<int64_t>(0, wall_now_us - clock_.movedWallUs());
}

bool ServiceContext::admit(const std::string& channel, const std::string& source, int64_t utime,
                           int64_t seq) {
  // One message stamped far ahead would move the clock past all real input, which then looks
  // stale until that time. The clock may lead by what passed on the wall clock meanwhile (idle
  // periods, paused replays) plus kMaxClockLeadUs (clock offsets between machines).
  const int64_t wall_now = wallTimeUs();
  const std::string key = channel + "|" + source;
  if (clock_.now() > 0 &&
      utime - clock_.now() > kMaxClockLeadUs + (wall_now - clock_.movedWallUs())) {
    auto [jump, fresh] = jumping_since_.try_emplace(key, wall_now, utime);
    if (!fresh && utime < jump->second.second) jump->second.first = wall_now;  // went back
    jump->second.second = utime;
    if (wall_now - jump->second.first < kClockResyncUs) {
      reject("rejected_time_jump", channel + " from " + source + ": utime jumps " +
                                       std::to_string((utime - clock_.now()) / 1000000) +
                                       " s ahead of the message clock");
      return false;
    }
    ++counters_["clock_resyncs"];
    logWarn(service_ + ": " + channel + " from " + source + " has stayed " +
            std::to_string((utime - clock_.now()) / 1000000) +
            " s ahead of the message clock for " + std::to_string(kClockResyncUs / 1000) +
            " ms: its clock moved, following it");
  }
  jumping_since_.erase(key);
  auto& last = last_in_[key];
  if (last.first > 0 && utime < last.first) {
    if (seq <= 1) {
      // The publisher restarted (its sequence starts again): accept its new clock.
      logInfo(service_ + ": " + channel + " from " + source + " restarted its clock");
    } else {
      reject("rejected_time_backwards", channel + " from " + source + ": utime went back by " +
                                            std::to_string(last.first - utime) + " us");
      return false;
    }
  }
  last = {utime, seq};
  return true;
}

void ServiceContext::setIncomingLoss(const std::string& base_channel, double fraction,
                                     uint64_t seed) {
  loss_[channel(base_channel)] = fraction;
  loss_rng_.seed(seed);
}

bool ServiceContext::dropForLoss(const std::string& channel) {
  auto it = loss_.find(channel);
  if (it == loss_.end() || it->second <= 0.0) return false;
  if (std::uniform_real_distribution<double>(0.0, 1.0)(loss_rng_) >= it->second) return false;
  ++counters_["test_dropped"];
  return true;
}

void ServiceContext::markRunning() {
  if (state_ == heartbeat_t::STATE_STARTING) setState(heartbeat_t::STATE_OK, "");
}

void ServiceContext::setState(int8_t state, const std::string& detail) {
  if (state != state_ || detail != state_detail_) {
    if (state == heartbeat_t::STATE_DEGRADED)
      logWarn(service_ + ": degraded: " + detail);
    else if (state_ == heartbeat_t::STATE_DEGRADED)
      logInfo(service_ + ": recovered");
  }
  state_ = state;
  state_detail_ = detail;
}

void ServiceContext::maybePublishHeartbeat(int64_t now_us, std::optional<int64_t> stamp_utime) {
  if (last_heartbeat_us_ >= 0 && now_us - last_heartbeat_us_ < 1'000'000) return;
  last_heartbeat_us_ = now_us;
  publishHeartbeat(stamp_utime);
}

void ServiceContext::publishHeartbeat(std::optional<int64_t> stamp_utime) {
  heartbeat_t hb{};
  // Never back in time (an input that arrives late pulls the estimate back): receivers would
  // refuse it.
  last_heartbeat_stamp_ =
      std::max(last_heartbeat_stamp_, stamp_utime ? *stamp_utime : estimatedNow(wallTimeUs()));
  hb.header.utime = last_heartbeat_stamp_;
  hb.service = service_;
  hb.host = host_;
  hb.pid = static_cast<int32_t>(getpid());
  hb.state = state_;
  hb.state_detail = state_detail_;
  hb.uptime_s = (wallTimeUs() - started_wall_us_) / 1'000'000;
  hb.msgs_in = msgs_in_;
  hb.msgs_out = msgs_out_;
  hb.msgs_rejected = msgs_rejected_;
  for (const auto& [name, value] : counters_) {
    hb.counter_names.push_back(name);
    hb.counter_values.push_back(value);
  }
  hb.num_counters = static_cast<int32_t>(hb.counter_names.size());
  publish(channels::kHeartbeat, hb);
}

int runNode(lcm::LCM& lcm, const std::vector<ServiceContext*>& contexts,
            const std::function<void()>& periodic, int poll_ms) {
  installStopHandlers();
  for (ServiceContext* c : contexts) {
    c->markRunning();
    c->maybePublishHeartbeat(wallTimeUs());
  }
  while (!stopRequested()) {
    const int status = lcm.handleTimeout(poll_ms);
    if (status < 0 && stopRequested()) break;  // the signal interrupted the wait
    if (status < 0) {
      // SIGINT/SIGTERM interrupt the wait (EINTR): that is a stop, not an LCM failure.
      if (stopRequested()) break;
      logError("LCM handle failed; stopping");
      return 1;
    }
    if (periodic) periodic();
    const int64_t now = wallTimeUs();
    for (ServiceContext* c : contexts) c->maybePublishHeartbeat(now);
  }
  for (ServiceContext* c : contexts) {
    c->setState(heartbeat_t::STATE_STOPPING, "signal received");
    c->publishHeartbeat();
  }
  logInfo("stopped cleanly");
  return 0;
}

}  // namespace mmh
