// mmh-log-summary: what happened in a recorded flight (lcm-logger or mmh-stack --log).
#include <iostream>

#include "log_summary.hpp"
#include "mmh/common/cli.hpp"

int main(int argc, char** argv) {
  std::vector<std::string> logs;
  mmh::ArgParser parser("mmh-log-summary",
                        "Channels and rates, planning iterations per mode, request-to-result "
                        "latency percentiles and LOCAL_MAP sequence gaps of an LCM log.");
  parser.addPositional("LOG...", &logs, "LCM log files");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  if (logs.empty()) {
    std::cerr << parser.usage();
    return 2;
  }
  int status = 0;
  for (const std::string& path : logs) {
    try {
      mmh::printSummary(mmh::summarizeLog(path), std::cout);
    } catch (const std::exception& e) {
      std::cerr << "mmh-log-summary: " << e.what() << "\n";
      status = 1;
    }
  }
  return status;
}
