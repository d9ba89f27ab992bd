// mmh-replan: gives every planning request of one mode in recorded flights to this build's
// planner, with the map the mode had then, and compares the answers with the recorded ones.
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "config_overrides.hpp"
#include "mmh/common/cli.hpp"
#include "mmh/common/node_options.hpp"
#include "replan.hpp"

int main(int argc, char** argv) {
  std::vector<std::string> sets;
  try {
    sets = mmh::takeSetOptions(&argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "mmh-replan: " << e.what() << "\n";
    return 2;
  }
  mmh::NodeOptions node;
  node.log_level = "error";
  mmh::ReplanOptions options;
  bool list = false;
  bool answers = false;
  std::vector<std::string> logs;
  std::string set_help;
  mmh::ArgParser parser(
      "mmh-replan",
      "Plans every PLAN_REQUEST_EAM (or _SOM, _FPM) of recorded flights (lcm-logger or mmh-stack "
      "--log) again with this build's planner and the map the mode had rebuilt from LOCAL_MAP "
      "then (FPM needs none), and compares with the recorded PLAN_RESULT: which failures are "
      "answered now, which answers fail now, and why.");
  parser.addString("--mode", &options.mode, "eam, som or fpm");
  parser.addString("--config", &node.config_path,
                   "configuration (default: $MMH_CONFIG or deploy/config/default.yaml)");
  parser.addString("--set", &set_help,
                   "key=value: override one configuration key (repeatable; a key of "
                   "docs/configuration.md, also one the file leaves out)");
  parser.addString("--prefix", &options.prefix, "channel prefix of the vehicle (default: none)");
  parser.addFlag("--list", &list, "one line per request that failed then or fails now");
  parser.addFlag("--answers", &answers,
                 "one line per request answered now: how far and how fast the answer flies "
                 "(duration, length, mean and top speed, jerk energy)");
  std::string trace_id;
  parser.addString("--trace", &trace_id,
                   "request id: print EAM's round-by-round trace of that request (one log)");
  std::string samples_id;
  parser.addString("--samples", &samples_id,
                   "request id: print that request, the path the mode searched and its answer (or "
                   "the trajectory it refused) every 0.05 s: position, speed, acceleration, jerk");
  parser.addPositional("LOG", &logs, "LCM logs of flights");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  if (logs.empty()) {
    std::cerr << parser.usage();
    return 2;
  }
  if (!trace_id.empty()) {
    char* end = nullptr;
    options.trace_request_id = std::strtoll(trace_id.c_str(), &end, 10);
    if (end == trace_id.c_str() || *end != '\0' || options.mode != "eam") {
      std::cerr << "mmh-replan: --trace takes a request id and works with --mode eam\n";
      return 2;
    }
    options.trace = &std::cout;
  }
  if (!samples_id.empty()) {
    char* end = nullptr;
    options.samples_request_id = std::strtoll(samples_id.c_str(), &end, 10);
    if (end == samples_id.c_str() || *end != '\0') {
      std::cerr << "mmh-replan: --samples takes a request id\n";
      return 2;
    }
    options.samples = &std::cout;
  }
  try {
    options.config = mmh::loadConfigWithOverrides(node, sets);
  } catch (const std::exception& e) {
    std::cerr << "mmh-replan: " << e.what() << "\n";
    return 2;
  }
  std::vector<mmh::ReplanOutcome> all;
  try {
    for (const std::string& path : logs) {
      const std::vector<mmh::ReplanOutcome> outcomes = mmh::replanLog(path, options);
      if (list) {
        for (const mmh::ReplanOutcome& o : outcomes) {
          if (o.ok && o.logged_ok) continue;
          std::printf("%s %7.2f s  request %lld  %.2f m/s  %.2f m/s^2  then: %s  now: %s\n",
                      path.c_str(), o.t_s, static_cast<long long>(o.request_id), o.start_speed_mps,
                      o.start_acceleration_mps2,
                      !o.logged_answer ? "no answer"
                      : o.logged_ok    ? "ok"
                                       : o.logged_detail.c_str(),
                      o.ok ? "ok" : o.detail.c_str());
        }
      }
      if (answers) {
        for (const mmh::ReplanOutcome& o : outcomes) {
          if (!o.ok) continue;
          std::printf(
              "%s %7.2f s  request %lld  from %.2f m/s  target %.2f m away: %.2f s, %.2f m, mean "
              "%.2f m/s, top %.2f m/s, energy %.1f m^2/s^5\n",
              path.c_str(), o.t_s, static_cast<long long>(o.request_id), o.start_speed_mps,
              o.target_distance_m, o.duration_s, o.length_m,
              o.duration_s > 0.0 ? o.length_m / o.duration_s : 0.0, o.max_speed_mps, o.jerk_energy);
        }
      }
      all.insert(all.end(), outcomes.begin(), outcomes.end());
    }
  } catch (const std::exception& e) {
    std::cerr << "mmh-replan: " << e.what() << "\n";
    return 2;
  }
  std::cout << "mode " << options.mode << ", " << logs.size() << " log(s)\n";
  mmh::printReplanSummary(mmh::summarize(all), std::cout);
  return 0;
}
