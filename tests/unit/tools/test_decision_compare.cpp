// mmh-replay's comparison of recorded and replayed decisions on hand-made sequences.
#include <gtest/gtest.h>

#include "decision_compare.hpp"

namespace mmh {
namespace {

Decision decision(int trigger, int committed_mode, int outcome = 1) {
  Decision d;
  d.trigger = trigger;
  d.outcome = outcome;
  d.committed_mode = committed_mode;
  d.modes_asked = committed_mode ? 1 << committed_mode : 0;
  return d;
}

TEST(DecisionCompare, IdenticalSequencesMatchWithoutDivergence) {
  const std::vector<Decision> a = {decision(1, 1), decision(2, 2), decision(3, 3)};
  const DecisionComparison c = compareDecisions(a, a);
  EXPECT_EQ(c.matched, 3u);
  EXPECT_FALSE(c.diverged);
  EXPECT_DOUBLE_EQ(c.matchedShare(), 1.0);
  EXPECT_TRUE(c.aligned);
}

TEST(DecisionCompare, PositionAndDetailDoNotMatter) {
  Decision a = decision(2, 2), b = decision(2, 2);
  b.x = 5.0;
  b.detail = "other words";
  EXPECT_EQ(compareDecisions({a}, {b}).matched, 1u);
  b.modes_asked |= 1 << 3;  // asked EAM as well: a different decision
  EXPECT_EQ(compareDecisions({a}, {b}).matched, 0u);
}

TEST(DecisionCompare, AnInsertedDecisionCostsOneAndIsTheFirstDivergence) {
  const std::vector<Decision> recorded = {decision(1, 1), decision(2, 2), decision(2, 2),
                                          decision(3, 3)};
  std::vector<Decision> replayed = recorded;
  replayed.insert(replayed.begin() + 1, decision(5, 4, 3));  // a stop in between
  const DecisionComparison c = compareDecisions(recorded, replayed);
  EXPECT_EQ(c.matched, 4u);
  ASSERT_TRUE(c.diverged);
  EXPECT_EQ(c.first_divergence, 1u);
  ASSERT_EQ(c.diff.size(), 5u);
  EXPECT_EQ(c.diff[1].kind, '+');
}

TEST(DecisionCompare, AShorterReplayDivergesWhereItEnds) {
  const std::vector<Decision> recorded = {decision(1, 1), decision(2, 2)};
  const DecisionComparison c = compareDecisions(recorded, {decision(1, 1)});
  EXPECT_EQ(c.matched, 1u);
  ASSERT_TRUE(c.diverged);
  EXPECT_EQ(c.first_divergence, 1u);
  EXPECT_DOUBLE_EQ(c.matchedShare(), 0.5);
}

TEST(DecisionCompare, TooLongForTheAlignmentIsComparedIndexByIndex) {
  const std::vector<Decision> recorded = {decision(1, 1), decision(2, 2), decision(3, 3)};
  const std::vector<Decision> replayed = {decision(5, 4, 3), decision(1, 1), decision(2, 2)};
  const DecisionComparison aligned = compareDecisions(recorded, replayed);
  EXPECT_EQ(aligned.matched, 2u);
  const DecisionComparison by_index = compareDecisions(recorded, replayed, 1);
  EXPECT_FALSE(by_index.aligned);
  EXPECT_EQ(by_index.matched, 0u);
  EXPECT_EQ(by_index.first_divergence, 0u);
}

TEST(DecisionCompare, CommitCountsPerMode) {
  EXPECT_EQ(commitCounts({decision(1, 1), decision(2, 2), decision(2, 2), decision(5, 0, 2)}),
            "FPM 1  SOM 2");
  EXPECT_EQ(commitCounts({}), "none");
}

}  // namespace
}  // namespace mmh
