// mmh-fpm: Fast Planning Mode as an LCM service (PLAN_REQUEST_FPM -> PLAN_RESULT).
#include <iostream>

#include "fpm_node.hpp"
#include "mmh/common/node_options.hpp"

int main(int argc, char** argv) {
  mmh::NodeOptions options;
  mmh::ArgParser parser("mmh-fpm",
                        "Fast Planning Mode: answers PLAN_REQUEST_FPM with a time-efficient "
                        "polynomial trajectory under the speed and acceleration limits.");
  mmh::addNodeOptions(parser, &options);
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  mmh::setLogServiceName("mmh-fpm");
  try {
    const mmh::Config config = mmh::loadNodeConfig(options);
    auto lcm = mmh::openLcm(options.lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-fpm", options.prefix);
    mmh::FpmNode node(ctx, config);
    return mmh::runNode(*lcm, {&ctx});
  } catch (const mmh::ConfigError& e) {
    std::cerr << "mmh-fpm: " << e.what() << "\n";
    return 1;
  } catch (const mmh::LcmError& e) {
    std::cerr << "mmh-fpm: " << e.what() << "\n";
    return 1;
  }
}
