#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "mmh/common/local_map_codec.hpp"

using Eigen::Vector3i;
using mmh::LocalMapReceiver;
using mmh::Occupancy;
using mmh::VoxelGrid;

namespace {

VoxelGrid randomGrid(const Vector3i& origin, uint32_t seed) {
  VoxelGrid g(0.1, origin, Vector3i(30, 20, 10));
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> state(0, 9);
  for (int64_t i = 0; i < g.numCells(); ++i) {
    const int s = state(rng);
    g.setLinear(i, s < 5 ? Occupancy::kUnknown : (s < 8 ? Occupancy::kFree : Occupancy::kOccupied));
  }
  return g;
}

bool sameCells(const VoxelGrid& a, const VoxelGrid& b) {
  return a.originIndex() == b.originIndex() && a.size() == b.size() && a.rawCells() == b.rawCells();
}

}  // namespace

TEST(LocalMapCodec, KeyframeRoundTrip) {
  VoxelGrid g = randomGrid(Vector3i(-10, 5, 0), 1);
  mmh::local_map_t msg = mmh::makeKeyframe(g, 1);
  EXPECT_EQ(msg.kind, mmh::local_map_t::KIND_KEYFRAME);
  LocalMapReceiver rx(0.2);
  ASSERT_EQ(rx.apply(msg), LocalMapReceiver::Result::kApplied);
  EXPECT_TRUE(sameCells(rx.grid(), g));
  EXPECT_EQ(rx.grid().inflationRadius(), 0.2);
}

TEST(LocalMapCodec, KeyframePlusDeltasRebuildTheSenderWindow) {
  VoxelGrid sender = randomGrid(Vector3i(0, 0, 0), 2);
  LocalMapReceiver rx;
  ASSERT_EQ(rx.apply(mmh::makeKeyframe(sender, 1)), LocalMapReceiver::Result::kApplied);
  std::mt19937 rng(3);
  for (int64_t seq = 2; seq < 12; ++seq) {
    // Move the window, then change some cells (as the mapping service does).
    VoxelGrid before = sender;
    sender.shiftTo(sender.originIndex() + Vector3i(seq % 3, -(seq % 2), 0));
    std::vector<mmh::CellChange> changes;
    for (int64_t i = 0; i < sender.numCells(); i += 1 + rng() % 40) {
      const Occupancy s = static_cast<Occupancy>(rng() % 3);
      if (sender.atLinear(i) != s) {
        sender.setLinear(i, s);
        changes.emplace_back(i, s);
      }
    }
    mmh::local_map_t delta = mmh::makeDelta(sender, seq, changes);
    ASSERT_EQ(rx.apply(delta), LocalMapReceiver::Result::kApplied);
    ASSERT_TRUE(sameCells(rx.grid(), sender)) << "after delta " << seq;
    EXPECT_EQ(rx.lastChangedCells().size(), changes.size());
  }
}

// The mapping service follows a keyframe scan's delta with the whole window of the same map: a
// receiver that applied the delta skips it, one that lost messages is healed by it, and a
// restarted sender's keyframe (same map_seq, another scan) is applied.
TEST(LocalMapCodec, TheKeyframeOfAMapItsDeltaBuiltIsSkipped) {
  VoxelGrid sender = randomGrid(Vector3i(0, 0, 0), 7);
  auto stamped = [](mmh::local_map_t msg, int64_t utime) {
    msg.header.utime = utime;
    return msg;
  };
  LocalMapReceiver rx, lost_it;
  ASSERT_EQ(rx.apply(stamped(mmh::makeKeyframe(sender, 1), 100)),
            LocalMapReceiver::Result::kApplied);
  const std::vector<mmh::CellChange> changes{{5, Occupancy::kOccupied}, {17, Occupancy::kFree}};
  for (const mmh::CellChange& c : changes) sender.setLinear(c.first, c.second);
  ASSERT_EQ(rx.apply(stamped(mmh::makeDelta(sender, 2, changes), 200)),
            LocalMapReceiver::Result::kApplied);
  const mmh::local_map_t keyframe = stamped(mmh::makeKeyframe(sender, 2), 200);
  std::string why;
  EXPECT_EQ(rx.apply(keyframe, &why), LocalMapReceiver::Result::kAlreadyBuilt);
  EXPECT_NE(why.find("already built"), std::string::npos) << why;
  EXPECT_TRUE(sameCells(rx.grid(), sender));
  EXPECT_EQ(lost_it.apply(keyframe), LocalMapReceiver::Result::kApplied);
  EXPECT_TRUE(sameCells(lost_it.grid(), sender));

  VoxelGrid restarted = randomGrid(Vector3i(0, 0, 0), 8);
  EXPECT_EQ(rx.apply(stamped(mmh::makeKeyframe(restarted, 2), 300)),
            LocalMapReceiver::Result::kApplied);
  EXPECT_TRUE(sameCells(rx.grid(), restarted));
}

TEST(LocalMapCodec, AKeyframeOnAMapItDiffersFromGivesWhatAFreshDecodeGives) {
  // The receiver holds an old map of the same window size; the keyframe is of another origin and
  // other cells. Only the differing cells are written, yet cells and inflation equal a fresh
  // receiver's.
  LocalMapReceiver rx(0.2);
  ASSERT_EQ(rx.apply(mmh::makeKeyframe(randomGrid(Vector3i(0, 0, 0), 5), 1)),
            LocalMapReceiver::Result::kApplied);
  const VoxelGrid sender = randomGrid(Vector3i(3, -2, 1), 6);
  const mmh::local_map_t keyframe = mmh::makeKeyframe(sender, 2);
  ASSERT_EQ(rx.apply(keyframe), LocalMapReceiver::Result::kApplied);
  LocalMapReceiver fresh(0.2);
  ASSERT_EQ(fresh.apply(keyframe), LocalMapReceiver::Result::kApplied);
  EXPECT_TRUE(sameCells(rx.grid(), sender));
  EXPECT_TRUE(rx.lastWasKeyframe());
  EXPECT_EQ(rx.mapSeq(), 2);
  EXPECT_EQ(rx.grid().numOccupied(), fresh.grid().numOccupied());
  const uint16_t* a = rx.grid().blockedCounts();
  const uint16_t* b = fresh.grid().blockedCounts();
  EXPECT_TRUE(std::equal(a, a + rx.grid().numCells(), b));
  // A malformed keyframe changes nothing.
  mmh::local_map_t bad = mmh::makeKeyframe(randomGrid(Vector3i(0, 0, 0), 7), 3);
  bad.runs.resize(bad.runs.size() / 2);
  bad.num_bytes = static_cast<int32_t>(bad.runs.size());
  EXPECT_EQ(rx.apply(bad), LocalMapReceiver::Result::kRejected);
  EXPECT_TRUE(sameCells(rx.grid(), sender));
  EXPECT_EQ(rx.mapSeq(), 2);
}

TEST(LocalMapCodec, GapIsDetectedAndKeyframeRecovers) {
  VoxelGrid sender = randomGrid(Vector3i(0, 0, 0), 4);
  LocalMapReceiver rx;
  // A delta before any keyframe is ignored.
  EXPECT_EQ(rx.apply(mmh::makeDelta(sender, 5, {})), LocalMapReceiver::Result::kWaitingForKeyframe);
  ASSERT_EQ(rx.apply(mmh::makeKeyframe(sender, 6)), LocalMapReceiver::Result::kApplied);
  ASSERT_EQ(rx.apply(mmh::makeDelta(sender, 7, {})), LocalMapReceiver::Result::kApplied);
  std::string why;
  EXPECT_EQ(rx.apply(mmh::makeDelta(sender, 9, {}), &why), LocalMapReceiver::Result::kGap);
  EXPECT_NE(why.find("gap"), std::string::npos);
  EXPECT_EQ(rx.gapsDetected(), 1);
  EXPECT_FALSE(rx.hasMap());
  EXPECT_EQ(rx.apply(mmh::makeDelta(sender, 10, {})),
            LocalMapReceiver::Result::kWaitingForKeyframe);
  EXPECT_EQ(rx.apply(mmh::makeKeyframe(sender, 11)), LocalMapReceiver::Result::kApplied);
  EXPECT_TRUE(rx.hasMap());
}

TEST(LocalMapCodec, ADeltaAppliesOnAnyMapFromItsBase) {
  VoxelGrid sender = randomGrid(Vector3i(0, 0, 0), 4);
  LocalMapReceiver rx;
  ASSERT_EQ(rx.apply(mmh::makeKeyframe(sender, 1)), LocalMapReceiver::Result::kApplied);
  ASSERT_EQ(rx.apply(mmh::makeDelta(sender, 2, {})), LocalMapReceiver::Result::kApplied);
  // Map 3 was lost; map 4 holds every change since map 2, so it applies on map 2.
  sender.set(Vector3i(1, 1, 1), Occupancy::kOccupied);
  const int64_t cell = sender.linearIndex(Vector3i(1, 1, 1));
  ASSERT_EQ(rx.apply(mmh::makeDelta(sender, 4, {{cell, Occupancy::kOccupied}}, 2)),
            LocalMapReceiver::Result::kApplied);
  EXPECT_TRUE(sameCells(rx.grid(), sender));
  EXPECT_EQ(rx.mapSeq(), 4);
  EXPECT_EQ(rx.lossesBridged(), 1);
  EXPECT_EQ(rx.gapsDetected(), 0);
  // A delta whose base is newer than the map held is a gap.
  EXPECT_EQ(rx.apply(mmh::makeDelta(sender, 7, {}, 5)), LocalMapReceiver::Result::kGap);
  // A base at or after map_seq is malformed.
  mmh::local_map_t bad = mmh::makeDelta(sender, 8, {}, 8);
  std::string why;
  EXPECT_FALSE(mmh::validateLocalMap(bad, &why));
  EXPECT_NE(why.find("base_seq"), std::string::npos);
}

TEST(LocalMapCodec, MalformedMessagesAreRejectedAndChangeNothing) {
  VoxelGrid sender = randomGrid(Vector3i(0, 0, 0), 5);
  LocalMapReceiver rx;
  ASSERT_EQ(rx.apply(mmh::makeKeyframe(sender, 1)), LocalMapReceiver::Result::kApplied);
  mmh::local_map_t bad = mmh::makeDelta(sender, 2, {{0, Occupancy::kOccupied}});
  bad.runs.push_back(0x80);  // truncated varint
  bad.num_bytes = static_cast<int32_t>(bad.runs.size());
  std::string why;
  EXPECT_EQ(rx.apply(bad, &why), LocalMapReceiver::Result::kRejected);
  EXPECT_FALSE(why.empty());

  mmh::local_map_t keyframe = mmh::makeKeyframe(sender, 3);
  keyframe.num_bytes += 1;  // length field disagrees with the data
  EXPECT_EQ(rx.apply(keyframe), LocalMapReceiver::Result::kRejected);
  keyframe = mmh::makeKeyframe(sender, 3);
  keyframe.size[0] = -4;
  EXPECT_EQ(rx.apply(keyframe), LocalMapReceiver::Result::kRejected);
  keyframe = mmh::makeKeyframe(sender, 3);
  keyframe.resolution_m = std::nan("");
  EXPECT_EQ(rx.apply(keyframe), LocalMapReceiver::Result::kRejected);
  // A run that leaves the window.
  keyframe = mmh::makeKeyframe(sender, 3);
  keyframe.size[2] = 1;
  EXPECT_EQ(rx.apply(keyframe), LocalMapReceiver::Result::kRejected);
  // The map the receiver had is intact.
  EXPECT_TRUE(sameCells(rx.grid(), sender));
}

TEST(LocalMapCodec, RunsAreCompactForCoherentChanges) {
  std::vector<mmh::CellChange> changes;
  for (int64_t i = 1000; i < 2000; ++i) changes.emplace_back(i, Occupancy::kFree);
  EXPECT_LE(mmh::encodeRuns(changes).size(), 5u);  // one run: skip, length, state
}
