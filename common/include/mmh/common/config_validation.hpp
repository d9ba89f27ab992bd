// Validation of a whole configuration file against the key registry, once, when a node starts
// (loadNodeConfig) and in mmh-config-check: a misspelt key would otherwise be ignored silently
// and its service would fly with another value.
#pragma once

#include <string>
#include <vector>

#include "mmh/common/config.hpp"

namespace mmh {

// Every problem, each a line naming the file and the key: unknown keys (with the nearest
// registered key), missing required keys, values of the wrong type or outside their range, and
// violated constraints between keys. Empty when the file is valid.
std::vector<std::string> configProblems(const Config& config);

// Throws ConfigError listing every problem.
void validateConfig(const Config& config);

}  // namespace mmh
