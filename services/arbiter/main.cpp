// mmh-arbiter: mode selection and lazy replanning, the only writer of TRAJECTORY.
#include <iostream>

#include "arbiter_node.hpp"
#include "mmh/common/node_options.hpp"

int main(int argc, char** argv) {
  mmh::NodeOptions options;
  std::string policy;
  mmh::ArgParser parser("mmh-arbiter",
                        "Chooses planning modes from AWARENESS, applies the lazy replanning rules "
                        "and commits TRAJECTORY.");
  mmh::addNodeOptions(parser, &options);
  parser.addString("--policy", &policy,
                   "override arbiter.policy: mmh, mmh-no-lazy, mmh-no-awareness, ego, som");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  mmh::setLogServiceName("mmh-arbiter");
  try {
    const mmh::Config config = mmh::loadNodeConfig(options);
    mmh::arbiter::ArbiterParams params = mmh::arbiter::loadArbiterParams(config);
    if (!policy.empty()) params.policy = mmh::arbiter::parsePolicy(policy);
    auto lcm = mmh::openLcm(options.lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-arbiter", options.prefix);
    mmh::ArbiterNode node(ctx, params);
    mmh::logInfo(std::string("policy ") + mmh::arbiter::toString(params.policy));
    return mmh::runNode(*lcm, {&ctx}, [&node] { node.onIdle(mmh::wallTimeUs()); });
  } catch (const std::exception& e) {
    std::cerr << "mmh-arbiter: " << e.what() << "\n";
    return 1;
  }
}
