#include "mmh/arbiter/fallback_chain.hpp"

namespace mmh::arbiter {

FallbackChain::FallbackChain(Policy policy) {
  switch (policy) {
    case Policy::kEgo:
      modes_ = {Mode::kEam};
      break;
    case Policy::kSom:
      modes_ = {Mode::kSom};
      break;
    default:
      modes_ = {Mode::kSom, Mode::kEam};
  }
}

void FallbackChain::beginRetry(Mode mode) {
  if (asked(mode)) reset();
}

std::optional<Mode> FallbackChain::next(int64_t map_seq) const {
  for (Mode m : modes_) {
    if (!asked(m)) return m;
  }
  if (map_seq != map_seq_at_failure_) return modes_.front();
  return std::nullopt;
}

bool FallbackChain::exhausted() const {
  for (Mode m : modes_) {
    if (!asked(m)) return false;
  }
  return true;
}

}  // namespace mmh::arbiter
