// Compares the recorded and the replayed sequence of arbiter decisions: the longest common
// subsequence says how many match, the first index where they differ is the first divergence.
#pragma once

#include <cstddef>
#include <ostream>
#include <vector>

#include "decision.hpp"

namespace mmh {

struct DecisionDiffLine {
  char kind = '=';  // '=' both, '-' recorded only, '+' replayed only
  const Decision* decision = nullptr;
};

struct DecisionComparison {
  size_t recorded = 0, replayed = 0;
  size_t matched = 0;  // decisions of a longest common subsequence (in order)
  bool diverged = false;
  size_t first_divergence = 0;  // index into both sequences, valid if diverged
  bool aligned = true;          // false: too long for the alignment, compared index by index
  std::vector<DecisionDiffLine> diff;
  double matchedShare() const { return recorded ? double(matched) / double(recorded) : 1.0; }
};

// Sequences longer than max_cells (recorded x replayed) are compared index by index.
DecisionComparison compareDecisions(const std::vector<Decision>& recorded,
                                    const std::vector<Decision>& replayed,
                                    size_t max_cells = 16'000'000);

// Counts per committed mode, e.g. "FPM 3  SOM 12  EAM 4  STOP 2".
std::string commitCounts(const std::vector<Decision>& decisions);

}  // namespace mmh
