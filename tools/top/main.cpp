// mmh-top: a terminal view of a running MMH system from HEARTBEAT and ARBITER_STATUS.
#include <iostream>

#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/node_options.hpp"
#include "top_view.hpp"

namespace {

struct TopNode {
  void onHeartbeat(const mmh::heartbeat_t& m, const std::string& ch) {
    view.onHeartbeat(m, ch, mmh::wallTimeUs());
  }
  void onStatus(const mmh::arbiter_status_t& m, const std::string& ch) {
    view.onArbiterStatus(m, ch, mmh::wallTimeUs());
  }
  mmh::TopView view;
};

}  // namespace

int main(int argc, char** argv) {
  std::string lcm_url, prefix = ".*";
  bool once = false;
  double interval_s = 1.0, duration_s = 3.0;
  mmh::ArgParser parser("mmh-top",
                        "Every service's host, state, message rates and rejected inputs, and each "
                        "vehicle's planning iterations and compute times, refreshed every second.");
  parser.addString("--lcm-url", &lcm_url, "LCM URL (default: $LCM_DEFAULT_URL or LCM's default)");
  parser.addString("--prefix", &prefix, "vehicle channel prefix to show (regex; default: all)");
  parser.addDouble("--interval", &interval_s, "screen refresh period (s)");
  parser.addFlag("--once", &once, "listen for --duration seconds, print one snapshot, exit");
  parser.addDouble("--duration", &duration_s, "with --once: how long to listen (s)");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  mmh::setLogServiceName("mmh-top");
  try {
    auto lcm = mmh::openLcm(lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-top", prefix);
    TopNode node;
    ctx.subscribe(mmh::channels::kHeartbeat, &TopNode::onHeartbeat, &node);
    ctx.subscribe(mmh::channels::kArbiterStatus, &TopNode::onStatus, &node);
    mmh::installStopHandlers();
    const int64_t start = mmh::wallTimeUs();
    int64_t next_draw = start + static_cast<int64_t>(interval_s * 1e6);
    while (!mmh::stopRequested()) {
      lcm->handleTimeout(50);
      const int64_t now = mmh::wallTimeUs();
      if (once && now - start >= duration_s * 1e6) {
        std::cout << node.view.render(now);
        return node.view.numServices() > 0 ? 0 : 1;
      }
      if (!once && now >= next_draw) {
        next_draw = now + static_cast<int64_t>(interval_s * 1e6);
        std::cout << "\033[2J\033[H"
                  << "mmh-top  (Ctrl-C to quit)\n\n"
                  << node.view.render(now) << std::flush;
      }
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "mmh-top: " << e.what() << "\n";
    return 1;
  }
}
