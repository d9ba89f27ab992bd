// What every MMH node shares: opening LCM with hard checks, channel prefixes, checked decoding
// and validation of every received message, counters, HEARTBEAT, the message clock, and a run
// loop that stops cleanly on SIGINT/SIGTERM. Several services may share one lcm::LCM (memq://
// in mmh-stack); each has its own ServiceContext.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "mmh/common/checked_decode.hpp"
#include "mmh/common/log.hpp"
#include "mmh/common/message_validation.hpp"
#include "mmh/heartbeat_t.hpp"

namespace mmh {

class LcmError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// LCM from `url`, or LCM_DEFAULT_URL, or LCM's default (udpm://239.255.76.67:7667?ttl=0).
// Throws LcmError with a hint when LCM is not usable (no multicast route, bad URL).
std::unique_ptr<lcm::LCM> openLcm(const std::string& url);

// Base channel names (docs/architecture.md, "Processes and channels"); the prefix is prepended by
// ServiceContext::channel.
namespace channels {
inline constexpr const char* kOdometry = "ODOMETRY";
inline constexpr const char* kPointcloud = "POINTCLOUD";
inline constexpr const char* kGoal = "GOAL";
inline constexpr const char* kLocalMap = "LOCAL_MAP";
inline constexpr const char* kAwareness = "AWARENESS";
inline constexpr const char* kPlanRequestFpm = "PLAN_REQUEST_FPM";
inline constexpr const char* kPlanRequestSom = "PLAN_REQUEST_SOM";
inline constexpr const char* kPlanRequestEam = "PLAN_REQUEST_EAM";
inline constexpr const char* kPlanResult = "PLAN_RESULT";
inline constexpr const char* kTrajectory = "TRAJECTORY";
inline constexpr const char* kArbiterStatus = "ARBITER_STATUS";
inline constexpr const char* kHeartbeat = "HEARTBEAT";
inline constexpr const char* kMissionStatus = "MISSION_STATUS";
inline constexpr const char* kSetpoint = "SETPOINT";
inline constexpr const char* kPlanDebug = "PLAN_DEBUG";  // som/eam.publish_debug only
}  // namespace channels

// Time of the newest message seen (microseconds of the message clock). Services never read the
// wall clock for decisions, so live, replayed and lock-step runs behave the same. The wall time
// at which the clock last moved is kept for ServiceContext::estimatedNow only.
class MessageClock {
 public:
  void observe(int64_t utime);
  int64_t now() const { return now_; }
  int64_t movedWallUs() const { return moved_wall_us_; }
  void reset() { now_ = moved_wall_us_ = 0; }

 private:
  int64_t now_ = 0;
  int64_t moved_wall_us_ = 0;
};

class ServiceContext;

namespace detail {
class SubscriptionBase {
 public:
  virtual ~SubscriptionBase() = default;
};
}  // namespace detail

class ServiceContext {
 public:
  ServiceContext(lcm::LCM& lcm, std::string service, std::string prefix);
  ~ServiceContext();
  ServiceContext(const ServiceContext&) = delete;
  ServiceContext& operator=(const ServiceContext&) = delete;

  const std::string& service() const { return service_; }
  const std::string& prefix() const { return prefix_; }
  std::string channel(const std::string& base) const { return prefix_ + base; }
  lcm::LCM& lcm() { return lcm_; }
  MessageClock& clock() { return clock_; }
  // The message clock moved on by the wall time that passed since an input last moved it: what
  // the inputs' time would be now had they kept coming. Lets a real-time service notice that
  // every input went silent (0 before the first input).
  int64_t estimatedNow(int64_t wall_now_us) const;

  // Delivers decoded and validated messages of `base_channel` to owner->method(msg). Messages
  // that fail to decode, fail validation, go back in time or jump ahead of the message clock
  // (more than kMaxClockLeadUs beyond the wall time since it last moved) are counted and logged,
  // not delivered.
  static constexpr int64_t kMaxClockLeadUs = 10'000'000;
  // A source whose messages on a channel all jump ahead, without going back, for this long on the
  // wall clock has really moved its clock (a simulator that caught up after being starved of the
  // CPU): its messages are delivered again and the message clock follows (`clock_resyncs`). A
  // single message stamped far ahead does not last that long.
  static constexpr int64_t kClockResyncUs = 1'000'000;
  template <class Msg, class Owner>
  void subscribe(const std::string& base_channel, void (Owner::*method)(const Msg&), Owner* owner);
  // Same, for handlers that need the full channel name (e.g. a regex subscription over all
  // vehicle prefixes: prefix ".*").
  template <class Msg, class Owner>
  void subscribe(const std::string& base_channel,
                 void (Owner::*method)(const Msg&, const std::string& channel), Owner* owner);

  // Sets header.source and a per-channel header.seq (and header.utime from the message clock if
  // the caller left it 0), then publishes on prefix + base_channel.
  template <class Msg>
  void publish(const std::string& base_channel, Msg& msg);

  // Counters (reported in HEARTBEAT). reject() also logs the reason, rate-limited per counter.
  void increment(const std::string& counter, int64_t n = 1) { counters_[counter] += n; }
  // Sets a counter to a library's own count (or a gauge to its value), for HEARTBEAT.
  void setCounter(const std::string& counter, int64_t value) { counters_[counter] = value; }
  int64_t counter(const std::string& name) const;
  void reject(const std::string& counter, const std::string& reason);
  int64_t messagesIn() const { return msgs_in_; }
  int64_t messagesOut() const { return msgs_out_; }
  int64_t messagesRejected() const { return msgs_rejected_; }

  void setState(int8_t state, const std::string& detail);
  int8_t state() const { return state_; }
  // STARTING -> OK once the service handles its inputs (runNode's loop, or a lock-step host's
  // first step); a state the service set itself (DEGRADED) stays.
  void markRunning();
  // Publishes HEARTBEAT if at least 1 s passed (on now_us's clock) since the last one. It is
  // stamped stamp_utime, by default estimatedNow() on the wall clock: the time it is sent, also
  // for a service whose inputs are rare (FPM between requests), so that a recorded flight's
  // heartbeats keep time with the flight. A lock-step host stamps its simulated time.
  void maybePublishHeartbeat(int64_t now_us, std::optional<int64_t> stamp_utime = std::nullopt);
  void publishHeartbeat(std::optional<int64_t> stamp_utime = std::nullopt);

  // Test-only loss switch: drop this fraction of the messages received on base_channel.
  // Every context also reads $MMH_TEST_INCOMING_LOSS ("LOCAL_MAP=0.3[,CHANNEL=F...]", base channel
  // names) at construction, so fault tests can make separate processes lossy; it logs a warning.
  void setIncomingLoss(const std::string& base_channel, double fraction, uint64_t seed = 1);

 private:
  template <class Msg, class Owner>
  class TypedSubscription;
  bool admit(const std::string& channel, const std::string& source, int64_t utime, int64_t seq);
  bool dropForLoss(const std::string& channel);
  void applyLossFromEnvironment();

  lcm::LCM& lcm_;
  std::string service_, prefix_, host_;
  MessageClock clock_;
  std::map<std::string, int64_t> counters_;
  std::map<std::string, LogLimiter> limiters_;
  std::map<std::string, int64_t> publish_seq_;
  std::map<std::string, std::pair<int64_t, int64_t>> last_in_;  // channel|source -> (utime, seq)
  // channel|source -> wall time of the first of the time jumps in a row and the last one's utime.
  std::map<std::string, std::pair<int64_t, int64_t>> jumping_since_;
  std::map<std::string, double> loss_;
  std::mt19937_64 loss_rng_{1};
  std::vector<std::unique_ptr<detail::SubscriptionBase>> subscriptions_;
  std::vector<lcm::Subscription*> lcm_subscriptions_;
  int64_t msgs_in_ = 0, msgs_out_ = 0, msgs_rejected_ = 0;
  int64_t last_heartbeat_stamp_ = 0;
  int8_t state_ = heartbeat_t::STATE_STARTING;
  std::string state_detail_;
  int64_t last_heartbeat_us_ = -1;
  int64_t started_wall_us_ = 0;
};

template <class Msg, class Owner>
class ServiceContext::TypedSubscription : public detail::SubscriptionBase {
 public:
  TypedSubscription(ServiceContext* ctx, void (Owner::*method)(const Msg&), Owner* owner)
      : ctx_(ctx), method_(method), owner_(owner) {}
  TypedSubscription(ServiceContext* ctx, void (Owner::*method)(const Msg&, const std::string&),
                    Owner* owner)
      : ctx_(ctx), method_with_channel_(method), owner_(owner) {}

  void onRaw(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    if (ctx_->dropForLoss(channel)) return;
    Msg msg;
    std::string why;
    const DecodeOutcome outcome = decodeChecked(rbuf->data, rbuf->data_size, msg, &why);
    if (outcome == DecodeOutcome::kUndecodable) {
      ctx_->reject("rejected_decode",
                   channel + ": cannot decode as " + Msg::getTypeName() + " (wrong type?)");
      return;
    }
    if (outcome == DecodeOutcome::kInvalid) {
      ctx_->reject("rejected_invalid", channel + ": " + why);
      return;
    }
    if (!ctx_->admit(channel, msg.header.source, msg.header.utime, msg.header.seq)) return;
    ctx_->clock_.observe(msg.header.utime);
    ++ctx_->msgs_in_;
    if (method_)
      (owner_->*method_)(msg);
    else
      (owner_->*method_with_channel_)(msg, channel);
  }

 private:
  ServiceContext* ctx_;
  void (Owner::*method_)(const Msg&) = nullptr;
  void (Owner::*method_with_channel_)(const Msg&, const std::string&) = nullptr;
  Owner* owner_;
};

template <class Msg, class Owner>
void ServiceContext::subscribe(const std::string& base_channel, void (Owner::*method)(const Msg&),
                               Owner* owner) {
  auto sub = std::make_unique<TypedSubscription<Msg, Owner>>(this, method, owner);
  lcm_subscriptions_.push_back(
      lcm_.subscribe(channel(base_channel), &TypedSubscription<Msg, Owner>::onRaw, sub.get()));
  subscriptions_.push_back(std::move(sub));
}

template <class Msg, class Owner>
void ServiceContext::subscribe(const std::string& base_channel,
                               void (Owner::*method)(const Msg&, const std::string& channel),
                               Owner* owner) {
  auto sub = std::make_unique<TypedSubscription<Msg, Owner>>(this, method, owner);
  lcm_subscriptions_.push_back(
      lcm_.subscribe(channel(base_channel), &TypedSubscription<Msg, Owner>::onRaw, sub.get()));
  subscriptions_.push_back(std::move(sub));
}

template <class Msg>
void ServiceContext::publish(const std::string& base_channel, Msg& msg) {
  const std::string full = channel(base_channel);
  msg.header.source = service_;
  msg.header.seq = ++publish_seq_[full];
  if (msg.header.utime == 0) msg.header.utime = clock_.now();
  if (lcm_.publish(full, &msg) != 0) {
    reject("publish_failed", full + ": lcm publish failed");
    return;
  }
  ++msgs_out_;
}

// Handles messages until SIGINT/SIGTERM (or until *stop becomes true). Heartbeats of every
// context go out at 1 Hz of wall-clock time; `periodic` is called at least every poll_ms.
// Returns 0 on a clean stop, 1 if LCM failed.
int runNode(lcm::LCM& lcm, const std::vector<ServiceContext*>& contexts,
            const std::function<void()>& periodic = {}, int poll_ms = 20);

// True once SIGINT or SIGTERM was received (after installStopHandlers()).
void installStopHandlers();
bool stopRequested();

int64_t wallTimeUs();

}  // namespace mmh
