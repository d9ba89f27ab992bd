// mmh-replay: feeds a recorded flight's inputs to mapping, awareness, the modes and the arbiter
// hosted in lock-step, and compares their decisions with the recorded ARBITER_STATUS.
#include <iostream>

#include "decision_compare.hpp"
#include "log_replay.hpp"
#include "mmh/common/cli.hpp"
#include "mmh/common/log.hpp"
#include "mmh/common/node_options.hpp"
#include "replay_report.hpp"

int main(int argc, char** argv) {
  mmh::NodeOptions node;
  node.log_level = "error";
  std::string policy, prefix;
  bool list = false, strict = false;
  std::vector<std::string> logs;
  mmh::ArgParser parser(
      "mmh-replay",
      "Replays the GOAL, ODOMETRY and POINTCLOUD of a recorded flight (lcm-logger or mmh-stack "
      "--log) into mapping, awareness, FPM, SOM, EAM and the arbiter in one process (memq://, "
      "lock-step) and compares the decisions with the recorded ARBITER_STATUS.");
  parser.addString("--config", &node.config_path,
                   "configuration (default: $MMH_CONFIG or deploy/config/default.yaml)");
  parser.addString("--policy", &policy, "arbiter policy (default: arbiter.policy of the config)");
  parser.addString("--prefix", &prefix,
                   "channel prefix of the vehicle (default: the only one in the log)");
  parser.addString("--log-level", &node.log_level, "services' log level: debug, info, warn, error");
  parser.addFlag("--list", &list, "list every decision, recorded and replayed, as a diff");
  parser.addFlag("--strict", &strict, "exit code 3 when a decision differs");
  parser.addPositional("LOG", &logs, "LCM log of a flight");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  if (logs.size() != 1) {
    std::cerr << parser.usage();
    return 2;
  }
  mmh::setLogServiceName("mmh-replay");
  mmh::ReplayOptions options;
  options.log_path = logs.front();
  options.policy = policy;
  options.prefix = prefix;
  options.auto_prefix = prefix.empty();
  try {
    options.config = mmh::loadNodeConfig(node);
  } catch (const std::exception& e) {
    std::cerr << "mmh-replay: " << e.what() << "\n";
    return 2;
  }
  try {
    const mmh::ReplayResult result = mmh::replayLog(options);
    const mmh::DecisionComparison comparison =
        mmh::compareDecisions(result.recorded, result.replayed);
    mmh::printReplayReport(options.log_path, policy, result, comparison, list, std::cout);
    return strict && comparison.diverged ? 3 : 0;
  } catch (const mmh::ReplayInputError& e) {
    std::cerr << "mmh-replay: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "mmh-replay: " << e.what() << "\n";
    return 1;
  }
}
