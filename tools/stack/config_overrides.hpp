// `--set key=value` for the lock-step tools (mmh-stack, mmh-bench): overrides of single keys of
// the YAML configuration, applied before any service reads it, so that one run can try another
// parameter without a copy of the file. Only keys that exist can be set: a typo must not pass
// silently as a key nobody reads.
#pragma once

#include <string>
#include <vector>

#include "mmh/common/config.hpp"
#include "mmh/common/node_options.hpp"

namespace mmh {

// Removes every "--set X" and "--set=X" from argv (argc shrinks) and returns the X in order. A
// trailing "--set" without a value is left for the parser to report.
std::vector<std::string> takeSetOptions(int* argc, char** argv);

// Parses the YAML text, replaces the value of each dotted key ("sim.step_s=0.02"; the value is
// YAML, so "[1, 2, 3]" is a list) and returns the configuration. Throws ConfigError naming the
// key when it does not exist, is a whole section, or the assignment has no "=".
Config applyConfigOverrides(const std::string& yaml_text, const std::string& source,
                            const std::vector<std::string>& assignments);

// loadNodeConfig (log level, the file of `options`) with the overrides applied.
Config loadConfigWithOverrides(const NodeOptions& options,
                               const std::vector<std::string>& assignments);

}  // namespace mmh
