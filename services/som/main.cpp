// mmh-som: Standard Optimization Mode service (A* -> safe flight corridor -> MINCO).
#include <iostream>

#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/log.hpp"
#include "mmh/common/node_options.hpp"
#include "som_node.hpp"

int main(int argc, char** argv) {
  mmh::NodeOptions options;
  mmh::ArgParser parser("mmh-som",
                        "Standard Optimization Mode: answers PLAN_REQUEST_SOM with a trajectory "
                        "through a safe flight corridor (A*, convex polytopes, MINCO).");
  mmh::addNodeOptions(parser, &options);
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  mmh::setLogServiceName("mmh-som");
  try {
    const mmh::Config config = mmh::loadNodeConfig(options);
    auto lcm = mmh::openLcm(options.lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-som", options.prefix);
    mmh::SomNode node(ctx, config);
    return mmh::runNode(*lcm, {&ctx});
  } catch (const mmh::ConfigError& e) {
    std::cerr << "mmh-som: " << e.what() << "\n";
    return 1;
  } catch (const mmh::LcmError& e) {
    std::cerr << "mmh-som: " << e.what() << "\n";
    return 1;
  }
}
