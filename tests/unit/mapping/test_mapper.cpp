// LOCAL_MAP production: keyframes and deltas rebuild exactly the sender's window, gaps are
// detected and healed by the next keyframe, deltas stay small in steady flight, and a keyframe
// scan sends its delta first.
#include <gtest/gtest.h>

#include <octomap/OcTree.h>
#include <algorithm>

#include "mapping_node.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/mapping/mapper.hpp"
#include "scan_helpers.hpp"

using Eigen::Vector3d;
using Result = mmh::LocalMapReceiver::Result;

namespace {

constexpr int64_t kT0 = 1'000'000'000;
constexpr int64_t kFrameUs = 66'667;

// A flight of 6 m along +x through a forest at 3 m/s (a frame every 0.2 m), turning a little.
struct Flight {
  mmh::sim::ForestWorld world = mmh::sim::ForestWorld::generate([] {
    mmh::ForestSpec spec;
    spec.density_per_m2 = 0.2;
    spec.seed = 2;
    spec.start = Vector3d(-3, 0, 1.2);
    spec.goal = Vector3d(3, 0, 1.2);
    spec.clearance_m = 1.0;
    return spec;
  }());
  std::vector<mmh::sim::Scan> scans;
  Flight() {
    for (int k = 0; k <= 30; ++k) {
      const Vector3d p(-3.0 + 0.2 * k, 0.0, 1.2);
      scans.push_back(mmh::test::scanOf(world, p, 15.0 * std::sin(0.3 * k)));
    }
  }
};

// The messages the node sends for one scan, in order.
std::vector<mmh::local_map_t> messagesOf(const mmh::mapping::Mapper& mapper,
                                         const mmh::mapping::Mapper::Result& r) {
  std::vector<mmh::local_map_t> out{mmh::toLocalMap(r.map)};
  if (r.keyframe_follows) out.push_back(mmh::toLocalMap(mapper.keyframe()));
  return out;
}

}  // namespace

TEST(Mapper, KeyframesAndDeltasRebuildTheSameMap) {
  Flight flight;
  mmh::mapping::MappingParams params;
  params.window_recenter_m = 0.5;  // several window moves within the flight
  mmh::mapping::Mapper mapper(params);
  mmh::LocalMapReceiver receiver;
  int keyframes = 0, moves = 0;
  for (size_t k = 0; k < flight.scans.size(); ++k) {
    const auto& scan = flight.scans[k];
    mapper.setVehiclePosition(scan.position);
    const auto r = mapper.processScan(mmh::test::inputOf(scan), kT0 + k * kFrameUs);
    ASSERT_EQ(r.error, mmh::mapping::ScanError::kNone);
    EXPECT_EQ(r.map.map_seq, static_cast<int64_t>(k + 1));
    EXPECT_EQ(r.map.utime, kT0 + static_cast<int64_t>(k) * kFrameUs);
    keyframes += r.map.keyframe || r.keyframe_follows;
    moves += r.window_moved;
    std::string why;
    const std::vector<mmh::local_map_t> messages = messagesOf(mapper, r);
    ASSERT_EQ(receiver.apply(messages.front(), &why), Result::kApplied) << why;
    // The receiver's window equals the sender's, cell for cell, after every scan's first message.
    ASSERT_EQ(receiver.grid().originIndex(), mapper.map().windowOrigin());
    ASSERT_EQ(receiver.grid().rawCells(), mapper.map().windowStates()) << "message " << k;
    if (messages.size() == 2) {
      // The whole window of the same map follows: nothing left to apply.
      EXPECT_EQ(messages.back().map_seq, messages.front().map_seq);
      EXPECT_EQ(messages.back().header.utime, messages.front().header.utime);
      EXPECT_EQ(receiver.apply(messages.back()), Result::kAlreadyBuilt);
    }
  }
  EXPECT_TRUE(flight.scans.size() > 15);
  EXPECT_EQ(keyframes, 3);  // the first, then one per second (15 frames)
  EXPECT_GE(moves, 5);
  EXPECT_GT(receiver.grid().numOccupied(), 500);
}

TEST(Mapper, AGapIsDetectedAndTheNextKeyframeHealsIt) {
  Flight flight;
  mmh::mapping::MappingParams params;
  params.delta_repeat = 1;  // every delta only from the previous message: one loss is a gap
  mmh::mapping::Mapper mapper(params);
  mmh::LocalMapReceiver receiver;
  std::vector<Result> results;
  for (size_t k = 0; k < flight.scans.size(); ++k) {
    const auto& scan = flight.scans[k];
    mapper.setVehiclePosition(scan.position);
    const auto r = mapper.processScan(mmh::test::inputOf(scan), kT0 + k * kFrameUs);
    if (k == 4) continue;  // lost on the network
    for (const mmh::local_map_t& msg : messagesOf(mapper, r))
      results.push_back(receiver.apply(msg));
    if (r.keyframe_follows) {
      EXPECT_EQ(results.end()[-2], Result::kWaitingForKeyframe);  // the scan's delta
      EXPECT_EQ(results.back(), Result::kApplied);                // its keyframe
      EXPECT_EQ(receiver.grid().rawCells(), mapper.map().windowStates());
      break;
    }
  }
  ASSERT_GE(results.size(), 6u);
  EXPECT_EQ(results[3], Result::kApplied);             // message 4 (k = 3)
  EXPECT_EQ(results[4], Result::kGap);                 // k = 5 after the lost k = 4
  EXPECT_EQ(results[5], Result::kWaitingForKeyframe);  // until the keyframe at k = 15
  EXPECT_EQ(receiver.gapsDetected(), 1);
}

TEST(Mapper, LossesShorterThanTheDeltaRepeatAreBridgedExactly) {
  Flight flight;
  mmh::mapping::MappingParams params;
  params.delta_repeat = 3;
  mmh::mapping::Mapper mapper(params);
  mmh::LocalMapReceiver receiver;
  // Lost on the network: one message (k = 4), two in a row (7, 8), then three in a row (11-13).
  const std::vector<size_t> lost{4, 7, 8, 11, 12, 13};
  std::vector<std::pair<size_t, Result>> results;
  for (size_t k = 0; k < flight.scans.size() && k < 16; ++k) {
    const auto& scan = flight.scans[k];
    mapper.setVehiclePosition(scan.position);
    const auto r = mapper.processScan(mmh::test::inputOf(scan), kT0 + k * kFrameUs);
    EXPECT_EQ(r.map.keyframe, k == 0) << k;
    EXPECT_EQ(r.keyframe_follows, k == 15) << k;
    if (std::find(lost.begin(), lost.end(), k) != lost.end()) continue;
    for (const mmh::local_map_t& msg : messagesOf(mapper, r)) {
      const Result applied = receiver.apply(msg);
      results.emplace_back(k, applied);
      if (applied == Result::kApplied) {
        // Exactly the sender's window, also right after the losses.
        ASSERT_EQ(receiver.grid().originIndex(), mapper.map().windowOrigin()) << k;
        ASSERT_EQ(receiver.grid().rawCells(), mapper.map().windowStates()) << k;
      }
    }
  }
  ASSERT_EQ(results.size(), 11u);
  for (size_t i = 0; i < results.size(); ++i) {
    const auto& [k, result] = results[i];
    if (k == 14)
      EXPECT_EQ(result, Result::kGap) << "three lost in a row are more than the repeat";
    else if (k == 15 && i + 1 < results.size())
      EXPECT_EQ(result, Result::kWaitingForKeyframe) << "the delta of the keyframe scan";
    else
      EXPECT_EQ(result, Result::kApplied) << k;  // the last is the keyframe that heals the gap
  }
  EXPECT_EQ(receiver.lossesBridged(), 2);  // k = 5 and k = 9
  EXPECT_EQ(receiver.gapsDetected(), 1);
}

TEST(Mapper, DeltasInSteadyFlightAreSmall) {
  Flight flight;
  mmh::mapping::MappingParams params;
  mmh::mapping::Mapper mapper(params);
  size_t max_delta = 0, keyframe = 0;
  for (size_t k = 0; k < flight.scans.size(); ++k) {
    const auto& scan = flight.scans[k];
    mapper.setVehiclePosition(scan.position);
    const auto r = mapper.processScan(mmh::test::inputOf(scan), kT0 + k * kFrameUs);
    for (const mmh::local_map_t& msg : messagesOf(mapper, r)) {
      const size_t bytes = static_cast<size_t>(msg.getEncodedSize());
      if (msg.kind == mmh::local_map_t::KIND_KEYFRAME)
        keyframe = std::max(keyframe, bytes);
      else if (k > 2)
        max_delta = std::max(max_delta, bytes);
    }
  }
  EXPECT_LT(max_delta, 64u * 1024u);
  EXPECT_GT(keyframe, max_delta);
}

// The node sends a keyframe scan's messages before the upkeep it calls for (maintain()): they are
// the same whether the upkeep runs right after each keyframe or only at the next scan, and after it
// the tree holds every known cell of the window.
TEST(Mapper, UpkeepAfterAKeyframeChangesNoMessage) {
  Flight flight;
  mmh::mapping::MappingParams params;
  params.window_recenter_m = 0.5;
  mmh::mapping::Mapper early(params), late(params);
  int upkeeps = 0;
  for (size_t k = 0; k < flight.scans.size(); ++k) {
    const auto& scan = flight.scans[k];
    early.setVehiclePosition(scan.position);
    late.setVehiclePosition(scan.position);
    const int64_t utime = kT0 + static_cast<int64_t>(k) * kFrameUs;
    const auto a = early.processScan(mmh::test::inputOf(scan), utime);
    const auto b = late.processScan(mmh::test::inputOf(scan), utime);
    const std::vector<mmh::local_map_t> sent_a = messagesOf(early, a), sent_b = messagesOf(late, b);
    ASSERT_EQ(sent_a.size(), sent_b.size()) << "message " << k;
    for (size_t i = 0; i < sent_a.size(); ++i)
      ASSERT_EQ(sent_a[i].runs, sent_b[i].runs) << "message " << k;
    if (!a.map.keyframe && !a.keyframe_follows) continue;
    early.maintain();
    ++upkeeps;
    // Every known window cell now has its leaf in the tree, with the window's state.
    const mmh::mapping::OccupancyMap& map = early.map();
    const Eigen::Vector3i size = map.windowSize();
    int checked = 0;
    for (int z = 0; z < size.z(); z += 3)
      for (int y = 0; y < size.y(); y += 3)
        for (int x = 0; x < size.x(); x += 3) {
          const Eigen::Vector3i g = map.windowOrigin() + Eigen::Vector3i(x, y, z);
          const Vector3d p = (g.cast<double>() + Vector3d::Constant(0.5)) * map.resolution();
          const mmh::Occupancy state = map.stateAt(p);
          if (state == mmh::Occupancy::kUnknown) continue;
          const octomap::OcTreeNode* node = map.octree().search(p.x(), p.y(), p.z());
          ASSERT_NE(node, nullptr) << "message " << k;
          EXPECT_EQ(map.octree().isNodeOccupied(node), state == mmh::Occupancy::kOccupied);
          ++checked;
        }
    EXPECT_GT(checked, 100);
  }
  EXPECT_EQ(upkeeps, 3);
}
