// The fallback chain of the arbiter (paper Sec. III.D, rule 4: "the last attempt failed"): after
// a failed round the modes are asked one after another (SOM, then EAM for the full method) until
// one answers. Once every mode was asked and failed, only a new map can change their answers, so
// the chain starts again from its first mode only on a map newer than the last failure.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "mmh/arbiter/arbiter_params.hpp"
#include "mmh/arbiter/modes.hpp"

namespace mmh::arbiter {

class FallbackChain {
 public:
  explicit FallbackChain(Policy policy);

  // A new episode of attempts (a commit, a new goal, a round that is not a retry).
  void reset() { asked_ = 0; }
  void markAsked(Mode mode) { asked_ |= modeBit(mode); }
  void recordFailure(int64_t map_seq) { map_seq_at_failure_ = map_seq; }
  // Before a retry round with `mode`: a mode asked already means the chain starts over.
  void beginRetry(Mode mode);

  // The next mode to retry with, given the newest map; none while the chain waits for a map.
  std::optional<Mode> next(int64_t map_seq) const;
  // Every mode of the chain was asked in this episode.
  bool exhausted() const;
  // The chain's modes in the order they are asked.
  const std::vector<Mode>& modes() const { return modes_; }

 private:
  bool asked(Mode mode) const { return (asked_ & modeBit(mode)) != 0; }

  std::vector<Mode> modes_;
  uint8_t asked_ = 0;  // bit mask (modeBit) of the modes asked in this episode
  int64_t map_seq_at_failure_ = 0;
};

}  // namespace mmh::arbiter
