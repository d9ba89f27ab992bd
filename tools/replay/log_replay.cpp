#include "log_replay.hpp"

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <memory>

#include "mmh/arbiter_status_t.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/goal_t.hpp"
#include "mmh/odometry_t.hpp"
#include "mmh/pointcloud_t.hpp"
#include "planner_host.hpp"

namespace mmh {
namespace {

std::unique_ptr<lcm::LogFile> openLog(const std::string& path) {
  auto log = std::make_unique<lcm::LogFile>(path, "r");
  if (!log->good()) throw ReplayInputError("cannot read LCM log " + path);
  return log;
}

bool endsWith(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() &&
         text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

struct RecordedEvent {
  std::string channel;
  std::vector<uint8_t> data;
};

template <class Msg>
bool decodeEvent(const void* data, int64_t size, Msg* msg) {
  try {
    return msg->decode(data, 0, static_cast<int>(size)) >= 0;
  } catch (const std::exception&) {
    return false;
  }
}

// Collects the ARBITER_STATUS that the hosted arbiter publishes.
class StatusCollector {
 public:
  void onStatus(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    arbiter_status_t msg;
    if (decodeEvent(rbuf->data, rbuf->data_size, &msg)) messages.push_back(msg);
  }
  std::vector<arbiter_status_t> messages;
};

// Message time of a recorded input, or -1 if it does not decode as its type.
template <class Msg>
int64_t messageTime(const lcm::LogEvent& e) {
  Msg msg;
  return decodeEvent(e.data, e.datalen, &msg) ? msg.header.utime : -1;
}

}  // namespace

std::set<std::string> inputPrefixes(const std::string& log_path) {
  auto log = openLog(log_path);
  std::set<std::string> prefixes;
  const std::string odometry = channels::kOdometry;
  while (const lcm::LogEvent* e = log->readNextEvent()) {
    if (endsWith(e->channel, odometry))
      prefixes.insert(e->channel.substr(0, e->channel.size() - odometry.size()));
  }
  return prefixes;
}

ReplayResult replayLog(const ReplayOptions& options) {
  ReplayResult result;
  result.prefix = options.prefix;
  if (options.auto_prefix && options.prefix.empty()) {
    const std::set<std::string> prefixes = inputPrefixes(options.log_path);
    if (prefixes.empty())
      throw ReplayInputError(options.log_path + " has no ODOMETRY channel: nothing to replay");
    if (prefixes.size() > 1) {
      std::string names;
      for (const std::string& p : prefixes) names += " \"" + p + "\"";
      throw ReplayInputError(options.log_path + " holds several vehicles (prefixes" + names +
                             "): choose one with --prefix");
    }
    result.prefix = *prefixes.begin();
  }
  const std::string& p = result.prefix;
  const std::string goal_ch = p + channels::kGoal, odom_ch = p + channels::kOdometry,
                    cloud_ch = p + channels::kPointcloud, status_ch = p + channels::kArbiterStatus;

  PlannerHostOptions host_options;
  host_options.config = options.config;
  host_options.prefix = p;
  host_options.policy = options.policy;
  PlannerHost host(host_options);
  StatusCollector replayed, recorded;
  host.lcm().subscribe(status_ch, &StatusCollector::onStatus, &replayed);

  auto log = openLog(options.log_path);
  const auto wall_start = std::chrono::steady_clock::now();
  // Inputs of one message time (one simulation step: ODOMETRY and POINTCLOUD) are published
  // together and then delivered, as the simulator does in lock-step.
  std::vector<RecordedEvent> batch;
  int64_t batch_utime = -1, first_utime = -1, last_utime = -1;
  auto flush = [&]() {
    if (batch.empty()) return;
    for (const RecordedEvent& e : batch)
      host.lcm().publish(e.channel, e.data.data(), static_cast<unsigned int>(e.data.size()));
    host.drain();
    if (batch_utime >= 0) host.advanceClocks(batch_utime);
    batch.clear();
    ++result.steps;
  };
  while (const lcm::LogEvent* e = log->readNextEvent()) {
    ++result.events;
    int64_t utime = -1;
    if (e->channel == goal_ch) {
      utime = messageTime<goal_t>(*e);
      ++result.goals;
    } else if (e->channel == odom_ch) {
      utime = messageTime<odometry_t>(*e);
      ++result.odometry;
    } else if (e->channel == cloud_ch) {
      utime = messageTime<pointcloud_t>(*e);
      ++result.pointclouds;
    } else if (e->channel == status_ch) {
      arbiter_status_t msg;
      if (decodeEvent(e->data, e->datalen, &msg)) recorded.messages.push_back(msg);
      continue;
    } else {
      continue;
    }
    if (utime < 0) {
      ++result.undecodable;  // fed anyway: the services count and reject it as in the flight
    } else {
      if (first_utime < 0 && e->channel == odom_ch) first_utime = utime;
      last_utime = std::max(last_utime, utime);
    }
    if (utime != batch_utime) flush();
    batch_utime = utime;
    const auto* bytes = static_cast<const uint8_t*>(e->data);
    batch.push_back({e->channel, std::vector<uint8_t>(bytes, bytes + e->datalen)});
  }
  flush();
  result.wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  if (result.odometry == 0)
    throw ReplayInputError(options.log_path + " has no " + odom_ch + ": nothing to replay");
  result.flight_s = (last_utime - first_utime) * 1e-6;
  for (const arbiter_status_t& msg : recorded.messages)
    result.recorded.push_back(decisionOf(msg, first_utime));
  for (const arbiter_status_t& msg : replayed.messages)
    result.replayed.push_back(decisionOf(msg, first_utime));
  return result;
}

}  // namespace mmh
