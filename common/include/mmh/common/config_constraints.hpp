// Constraints between configuration keys, often of different services (the planners' start
// escape must stay outside the arbiter's check margin, ...). They are checked at load, by the
// node's start-up validation and by the parameter loaders, with messages naming both keys.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "mmh/common/config.hpp"

namespace mmh {

struct ConfigConstraint {
  std::vector<std::string> keys;  // every key it relates (all registered)
  std::string rule;               // e.g. "arbiter.check_inflation_m <= map.inflation_m"
  std::string why;                // one line for the message and the documentation
  // "" when satisfied, else what is wrong with the values (the caller adds file and reason).
  std::function<std::string(const Config&)> violation;
};

const std::vector<ConfigConstraint>& configConstraints();

// One message per violated constraint among those whose keys the config holds or defaults (a
// partial config, e.g. a test's snippet, is checked on what it has). Values that cannot be read
// are skipped here: reading them reports them.
std::vector<std::string> constraintViolations(const Config& config);
// Throws ConfigError with every violation.
void checkConfigConstraints(const Config& config);

}  // namespace mmh
