// mmh-eam: Emergency Avoidance Mode as a process. Reads LOCAL_MAP and PLAN_REQUEST_EAM, writes
// PLAN_RESULT (and HEARTBEAT).
#include <iostream>

#include "eam_node.hpp"
#include "mmh/common/node_options.hpp"

int main(int argc, char** argv) {
  mmh::NodeOptions options;
  mmh::ArgParser parser("mmh-eam",
                        "Emergency Avoidance Mode: ESDF-free B-spline optimisation with "
                        "narrow-space weights; answers PLAN_REQUEST_EAM with PLAN_RESULT.");
  mmh::addNodeOptions(parser, &options);
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  mmh::setLogServiceName("mmh-eam");
  try {
    const mmh::Config config = mmh::loadNodeConfig(options);
    auto lcm = mmh::openLcm(options.lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-eam", options.prefix);
    mmh::EamNode node(ctx, config);
    mmh::logInfo("listening on " + ctx.channel(mmh::channels::kPlanRequestEam));
    return mmh::runNode(*lcm, {&ctx});
  } catch (const mmh::ConfigError& e) {
    std::cerr << "mmh-eam: " << e.what() << "\n";
    return 1;
  } catch (const mmh::LcmError& e) {
    std::cerr << "mmh-eam: " << e.what() << "\n";
    return 1;
  }
}
