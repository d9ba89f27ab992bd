// mmh-replay's report: what was fed, how many decisions matched or differed, the first
// divergence, and with `list` every decision as a diff (= both, - recorded only, + replayed only).
#pragma once

#include <ostream>
#include <string>

#include "decision_compare.hpp"
#include "log_replay.hpp"

namespace mmh {

void printReplayReport(const std::string& log_path, const std::string& policy,
                       const ReplayResult& result, const DecisionComparison& comparison, bool list,
                       std::ostream& out);

}  // namespace mmh
