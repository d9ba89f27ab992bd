// mmh-lcm-check: is LCM traffic getting through between two processes or machines?
// One side runs `--send`, the other `--receive`; the receiver exits 0 once it has seen the
// expected number of valid messages (decoded and validated by the same runtime the services use).
#include <iostream>
#include <thread>

#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/node_options.hpp"
#include "mmh/goal_t.hpp"

namespace {

class Receiver {
 public:
  void onGoal(const mmh::goal_t& msg) {
    ++received;
    last_id = msg.goal_id;
  }
  int received = 0;
  int64_t last_id = 0;
};

}  // namespace

int main(int argc, char** argv) {
  mmh::NodeOptions node;
  bool send = false, receive = false;
  int count = 10;
  double timeout_s = 10.0, period_s = 0.1;
  std::string channel = "LCM_CHECK";
  mmh::ArgParser parser("mmh-lcm-check",
                        "Checks that LCM messages travel between two processes or machines.");
  mmh::addNodeOptions(parser, &node);
  parser.addFlag("--send", &send, "publish test messages");
  parser.addFlag("--receive", &receive, "wait for test messages");
  parser.addInt("--count", &count, "messages to send / to wait for");
  parser.addDouble("--timeout", &timeout_s, "receiver gives up after this many seconds");
  parser.addDouble("--period", &period_s, "sender's interval between messages (s)");
  parser.addString("--channel", &channel, "base channel name");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  if (send == receive) {
    std::cerr << "mmh-lcm-check: give exactly one of --send or --receive\n";
    return 2;
  }
  mmh::setLogServiceName("mmh-lcm-check");
  try {
    auto lcm = mmh::openLcm(node.lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-lcm-check", node.prefix);
    mmh::installStopHandlers();
    if (send) {
      for (int i = 1; i <= count && !mmh::stopRequested(); ++i) {
        mmh::goal_t msg{};
        msg.header.utime = mmh::wallTimeUs();
        msg.goal_id = i;
        ctx.publish(channel, msg);
        std::this_thread::sleep_for(std::chrono::duration<double>(period_s));
      }
      std::cout << "sent " << count << " messages on " << ctx.channel(channel) << "\n";
      return 0;
    }
    Receiver receiver;
    ctx.subscribe(channel, &Receiver::onGoal, &receiver);
    const int64_t deadline = mmh::wallTimeUs() + static_cast<int64_t>(timeout_s * 1e6);
    while (receiver.received < count && mmh::wallTimeUs() < deadline && !mmh::stopRequested()) {
      lcm->handleTimeout(50);
    }
    std::cout << "received " << receiver.received << " of " << count << " messages on "
              << ctx.channel(channel) << "\n";
    return receiver.received >= count ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "mmh-lcm-check: " << e.what() << "\n";
    return 1;
  }
}
