// Every message of mmh-bad-input's catalogue, published on memq:// at a ServiceContext that
// subscribes every channel with its type: those meant for the runtime (undecodable, invalid,
// going back in time) are refused with that counter and never delivered; the rest pass the
// runtime and are the services' to refuse (empty scan, goal outside the fence, ...).
#include <gtest/gtest.h>

#include <set>

#include "bad_messages.hpp"
#include "mmh/awareness_t.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/goal_t.hpp"
#include "mmh/local_map_t.hpp"
#include "mmh/odometry_t.hpp"
#include "mmh/plan_request_t.hpp"
#include "mmh/plan_result_t.hpp"
#include "mmh/pointcloud_t.hpp"
#include "mmh/trajectory_t.hpp"

namespace {

using mmh::bad_input::BadMessage;

struct Sink {
  int delivered = 0;
  void onOdometry(const mmh::odometry_t&) { ++delivered; }
  void onPointcloud(const mmh::pointcloud_t&) { ++delivered; }
  void onGoal(const mmh::goal_t&) { ++delivered; }
  void onLocalMap(const mmh::local_map_t&) { ++delivered; }
  void onRequest(const mmh::plan_request_t&) { ++delivered; }
  void onResult(const mmh::plan_result_t&) { ++delivered; }
  void onAwareness(const mmh::awareness_t&) { ++delivered; }
  void onTrajectory(const mmh::trajectory_t&) { ++delivered; }
};

const std::set<std::string> kRuntimeCounters = {"rejected_decode", "rejected_invalid",
                                                "rejected_time_backwards", "rejected_time_jump"};

void checkCatalogue(mmh::bad_input::Target target) {
  auto lcm = mmh::openLcm("memq://");
  mmh::ServiceContext ctx(*lcm, "receiver", "");
  Sink sink;
  ctx.subscribe("ODOMETRY", &Sink::onOdometry, &sink);
  ctx.subscribe("POINTCLOUD", &Sink::onPointcloud, &sink);
  ctx.subscribe("GOAL", &Sink::onGoal, &sink);
  ctx.subscribe("LOCAL_MAP", &Sink::onLocalMap, &sink);
  for (const char* ch : {"PLAN_REQUEST_FPM", "PLAN_REQUEST_SOM", "PLAN_REQUEST_EAM"})
    ctx.subscribe(ch, &Sink::onRequest, &sink);
  ctx.subscribe("PLAN_RESULT", &Sink::onResult, &sink);
  ctx.subscribe("AWARENESS", &Sink::onAwareness, &sink);
  ctx.subscribe("TRAJECTORY", &Sink::onTrajectory, &sink);

  mmh::bad_input::CatalogueOptions options;
  options.utime0 = 1'700'000'000'000'000;
  options.huge_scan_points = 600;  // the size of the check, not of the message, matters here
  options.mapping_max_points = 500;
  const std::vector<BadMessage> messages = mmh::bad_input::makeBadMessages(target, options);
  ASSERT_GT(messages.size(), 5u);
  for (const BadMessage& m : messages) {
    std::set<std::string> runtime;
    for (const auto& e : m.expect) {
      if (kRuntimeCounters.count(e.counter)) runtime.insert(e.counter);
    }
    ASSERT_LE(runtime.size(), 1u) << m.name;
    const std::string counter = runtime.empty() ? "" : *runtime.begin();
    const int64_t before = counter.empty() ? 0 : ctx.counter(counter);
    const int delivered = sink.delivered;
    lcm->publish(m.channel, m.data.data(), static_cast<unsigned>(m.data.size()));
    while (lcm->handleTimeout(0) > 0) {
    }
    if (counter.empty()) {
      EXPECT_EQ(sink.delivered, delivered + 1) << m.name << ": should reach the service";
    } else {
      EXPECT_EQ(ctx.counter(counter), before + 1) << m.name << ": " << counter;
      EXPECT_EQ(sink.delivered, delivered) << m.name << ": must not be delivered";
    }
  }
}

}  // namespace

TEST(BadInputCatalogue, StackMessagesAreRefusedByTheRuntimeOrReachTheService) {
  checkCatalogue(mmh::bad_input::Target::kStack);
}

TEST(BadInputCatalogue, SimMessagesAreRefusedByTheRuntime) {
  checkCatalogue(mmh::bad_input::Target::kSim);
}

TEST(BadInputCatalogue, EveryMessageNamesWhatMustRise) {
  mmh::bad_input::CatalogueOptions options;
  options.huge_scan_points = 10;
  options.mapping_max_points = 5;
  for (auto target : {mmh::bad_input::Target::kStack, mmh::bad_input::Target::kSim}) {
    for (const BadMessage& m : mmh::bad_input::makeBadMessages(target, options)) {
      if (m.name.find("(good") != std::string::npos) continue;  // set-up messages
      EXPECT_FALSE(m.expect.empty()) << m.name;
    }
  }
}
