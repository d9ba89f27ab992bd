// The fallback chain (fallback_chain.hpp): the modes one after another, then a wait for a map.
#include <gtest/gtest.h>

#include "mmh/arbiter/fallback_chain.hpp"

using namespace mmh::arbiter;

TEST(FallbackChain, SomThenEamThenWaitsForANewerMap) {
  FallbackChain chain(Policy::kMmh);
  EXPECT_EQ(chain.next(1), Mode::kSom);
  chain.markAsked(Mode::kSom);
  chain.recordFailure(1);
  EXPECT_FALSE(chain.exhausted());
  EXPECT_EQ(chain.next(1), Mode::kEam);
  chain.markAsked(Mode::kEam);
  chain.recordFailure(1);
  EXPECT_TRUE(chain.exhausted());
  EXPECT_EQ(chain.next(1), std::nullopt);  // the same map gives the same answers
  EXPECT_EQ(chain.next(2), Mode::kSom);    // a newer one may not
  chain.beginRetry(Mode::kSom);
  EXPECT_FALSE(chain.exhausted());
  EXPECT_EQ(chain.next(2), Mode::kSom);
}

TEST(FallbackChain, AModeAskedOutsideTheChainCountsAsTried) {
  FallbackChain chain(Policy::kMmh);
  chain.markAsked(Mode::kEam);  // EAM on a collision failed: SOM is next, then the wait
  chain.markAsked(Mode::kFpm);  // FPM is not in the chain
  EXPECT_EQ(chain.next(1), Mode::kSom);
  chain.markAsked(Mode::kSom);
  chain.recordFailure(1);
  EXPECT_TRUE(chain.exhausted());
  chain.reset();
  EXPECT_EQ(chain.next(1), Mode::kSom);
}

TEST(FallbackChain, SingleModeBaselinesRetryTheirOwnMode) {
  FallbackChain ego(Policy::kEgo);
  EXPECT_EQ(ego.next(1), Mode::kEam);
  ego.markAsked(Mode::kEam);
  ego.recordFailure(1);
  EXPECT_TRUE(ego.exhausted());
  EXPECT_EQ(ego.next(2), Mode::kEam);
  FallbackChain som(Policy::kSom);
  EXPECT_EQ(som.next(1), Mode::kSom);
}
