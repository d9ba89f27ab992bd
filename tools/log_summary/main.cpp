// mmh-log-summary: what happened in a recorded flight (lcm-logger or mmh-stack --log).
#include <fstream>
#include <iostream>

#include "log_summary.hpp"
#include "mmh/common/cli.hpp"

int main(int argc, char** argv) {
  std::vector<std::string> logs;
  mmh::ArgParser parser("mmh-log-summary",
                        "Channels and rates, planning iterations per mode, request-to-result "
                        "latency percentiles and LOCAL_MAP sequence gaps of an LCM log.");
  bool decisions = false, reactions = false;
  std::string export_path, prefix;
  parser.addString("--export-flight", &export_path,
                   "write the flight (path, decisions, mapped obstacles) as JSON for "
                   "tools/plot_flight.py");
  parser.addString("--prefix", &prefix, "with --export-flight: the vehicle's channel prefix");
  parser.addFlag("--decisions", &decisions, "also list every arbiter decision");
  parser.addFlag("--reactions", &reactions,
                 "print only the reaction times (ms), one per line: newly mapped danger to the "
                 "answer committed, of every log (to pool percentiles over many flights)");
  parser.addPositional("LOG...", &logs, "LCM log files");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  if (logs.empty()) {
    std::cerr << parser.usage();
    return 2;
  }
  int status = 0;
  if (!export_path.empty()) {
    try {
      std::ofstream out(export_path);
      mmh::exportFlight(logs.front(), prefix, out);
      return 0;
    } catch (const std::exception& e) {
      std::cerr << "mmh-log-summary: " << e.what() << "\n";
      return 1;
    }
  }
  for (const std::string& path : logs) {
    try {
      const mmh::LogSummary summary = mmh::summarizeLog(path);
      if (reactions) {
        for (const auto& [prefix_seen, v] : summary.vehicles) {
          for (double ms : v.reaction_ms) std::cout << ms << "\n";
        }
        continue;
      }
      mmh::printSummary(summary, std::cout);
      if (decisions) mmh::printDecisions(summary, std::cout);
    } catch (const std::exception& e) {
      std::cerr << "mmh-log-summary: " << e.what() << "\n";
      status = 1;
    }
  }
  return status;
}
