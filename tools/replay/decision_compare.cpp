#include "decision_compare.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <sstream>
#include <string>

#include "mmh/common/decision_names.hpp"

namespace mmh {
namespace {

void lcsDiff(const std::vector<Decision>& a, const std::vector<Decision>& b,
             DecisionComparison* out) {
  const size_t n = a.size(), m = b.size();
  // L[i][j] = LCS length of a[i..] and b[j..]; fits 16 bits because min(n, m) is small here.
  std::vector<uint16_t> L((n + 1) * (m + 1), 0);
  auto at = [&](size_t i, size_t j) -> uint16_t& { return L[i * (m + 1) + j]; };
  for (size_t i = n; i-- > 0;) {
    for (size_t j = m; j-- > 0;) {
      at(i, j) = a[i].sameAs(b[j]) ? static_cast<uint16_t>(at(i + 1, j + 1) + 1)
                                   : std::max(at(i + 1, j), at(i, j + 1));
    }
  }
  size_t i = 0, j = 0;
  while (i < n || j < m) {
    if (i < n && j < m && a[i].sameAs(b[j])) {
      out->diff.push_back({'=', &a[i++]});
      ++j;
      ++out->matched;
    } else if (j >= m || (i < n && at(i + 1, j) >= at(i, j + 1))) {
      out->diff.push_back({'-', &a[i++]});
    } else {
      out->diff.push_back({'+', &b[j++]});
    }
  }
}

void indexDiff(const std::vector<Decision>& a, const std::vector<Decision>& b,
               DecisionComparison* out) {
  out->aligned = false;
  for (size_t i = 0; i < std::max(a.size(), b.size()); ++i) {
    if (i < a.size() && i < b.size() && a[i].sameAs(b[i])) {
      out->diff.push_back({'=', &a[i]});
      ++out->matched;
      continue;
    }
    if (i < a.size()) out->diff.push_back({'-', &a[i]});
    if (i < b.size()) out->diff.push_back({'+', &b[i]});
  }
}

}  // namespace

DecisionComparison compareDecisions(const std::vector<Decision>& recorded,
                                    const std::vector<Decision>& replayed, size_t max_cells) {
  DecisionComparison c;
  c.recorded = recorded.size();
  c.replayed = replayed.size();
  const size_t shorter = std::min(recorded.size(), replayed.size());
  if (shorter < UINT16_MAX && (recorded.size() + 1) * (replayed.size() + 1) <= max_cells) {
    lcsDiff(recorded, replayed, &c);
  } else {
    indexDiff(recorded, replayed, &c);
  }
  for (size_t i = 0; i < std::max(recorded.size(), replayed.size()); ++i) {
    if (i >= shorter || !recorded[i].sameAs(replayed[i])) {
      c.diverged = true;
      c.first_divergence = i;
      break;
    }
  }
  return c;
}

std::string commitCounts(const std::vector<Decision>& decisions) {
  std::map<int, int> counts;
  for (const Decision& d : decisions) {
    if (d.committed_mode != 0) ++counts[d.committed_mode];
  }
  std::ostringstream out;
  for (const auto& [mode, n] : counts)
    out << (out.tellp() > 0 ? "  " : "") << modeName(mode) << " " << n;
  return counts.empty() ? "none" : out.str();
}

}  // namespace mmh
