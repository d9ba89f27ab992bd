// mmh-mapping: the probabilistic map as a process. Reads POINTCLOUD and ODOMETRY, writes
// LOCAL_MAP (and HEARTBEAT).
#include <iostream>

#include "mapping_node.hpp"
#include "mmh/common/node_options.hpp"

int main(int argc, char** argv) {
  mmh::NodeOptions options;
  mmh::ArgParser parser("mmh-mapping",
                        "OctoMap mapping of POINTCLOUD scans; publishes the window around the "
                        "vehicle as LOCAL_MAP keyframes and deltas.");
  mmh::addNodeOptions(parser, &options);
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  mmh::setLogServiceName("mmh-mapping");
  try {
    const mmh::Config config = mmh::loadNodeConfig(options);
    auto lcm = mmh::openLcm(options.lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-mapping", options.prefix);
    mmh::MappingNode node(ctx, config);
    return mmh::runNode(*lcm, {&ctx});
  } catch (const mmh::ConfigError& e) {
    std::cerr << "mmh-mapping: " << e.what() << "\n";
    return 1;
  } catch (const mmh::LcmError& e) {
    std::cerr << "mmh-mapping: " << e.what() << "\n";
    return 1;
  }
}
