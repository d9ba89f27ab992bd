// mmh-config-check: validates configuration files as a node does at start-up, but lists every
// problem (unknown keys, missing keys, ranges, constraints) — for users before a flight.
#include <iostream>

#include "mmh/common/cli.hpp"
#include "mmh/common/config_validation.hpp"
#include "mmh/common/node_options.hpp"

int main(int argc, char** argv) {
  std::vector<std::string> files;
  mmh::ArgParser parser("mmh-config-check",
                        "Validates configuration files against the key registry; exit 1 when "
                        "any has a problem.");
  parser.addPositional("FILE", &files,
                       "configuration files (default: $MMH_CONFIG or deploy/config/default.yaml)");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  if (files.empty()) files.push_back(mmh::defaultConfigPath());
  int status = 0;
  for (const std::string& file : files) {
    std::vector<std::string> problems;
    try {
      problems = mmh::configProblems(mmh::Config::loadFile(file));
    } catch (const mmh::ConfigError& e) {
      problems.push_back(e.what());
    }
    if (problems.empty()) {
      std::cout << file << ": OK\n";
      continue;
    }
    status = 1;
    for (const std::string& p : problems) std::cout << p << "\n";
  }
  return status;
}
