// mmh-awareness: goal-oriented spatial awareness (paper Algorithm 1) as an LCM service.
#include <iostream>

#include "awareness_node.hpp"
#include "mmh/common/node_options.hpp"

int main(int argc, char** argv) {
  mmh::NodeOptions options;
  mmh::ArgParser parser(
      "mmh-awareness",
      "Answers LOCAL_MAP / ODOMETRY / GOAL with AWARENESS: is the way towards the "
      "goal, within sensor range, free of obstacles and narrow passages?");
  mmh::addNodeOptions(parser, &options);
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  mmh::setLogServiceName("mmh-awareness");
  try {
    const mmh::Config config = mmh::loadNodeConfig(options);
    auto lcm = mmh::openLcm(options.lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-awareness", options.prefix);
    mmh::AwarenessNode node(ctx, config);
    return mmh::runNode(*lcm, {&ctx});
  } catch (const mmh::ConfigError& e) {
    std::cerr << "mmh-awareness: " << e.what() << "\n";
    return 1;
  } catch (const mmh::LcmError& e) {
    std::cerr << "mmh-awareness: " << e.what() << "\n";
    return 1;
  }
}
