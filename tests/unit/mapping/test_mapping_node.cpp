// MappingNode over memq://: LOCAL_MAP for good scans, counters and no crash for bad ones.
#include <gtest/gtest.h>

#include <limits>

#include "mapping_node.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/msg_convert.hpp"
#include "scan_helpers.hpp"

using Eigen::Vector3d;

namespace {

mmh::Config testConfig() {
  return mmh::Config::loadFile(std::string(MMH_SOURCE_DIR) + "/deploy/config/default.yaml");
}

struct MapListener {
  void onMap(const mmh::local_map_t& m) {
    maps.push_back(m);
    results.push_back(receiver.apply(m));
  }
  std::vector<mmh::local_map_t> maps;
  std::vector<mmh::LocalMapReceiver::Result> results;
  mmh::LocalMapReceiver receiver;
};

mmh::pointcloud_t cloudOf(const mmh::sim::Scan& scan, int64_t utime) {
  mmh::pointcloud_t msg{};
  msg.header.utime = utime;
  msg.sensor_kind = mmh::pointcloud_t::SENSOR_DEPTH;
  mmh::fromVec3(scan.position, msg.sensor_position);
  msg.sensor_orientation[0] = 1.0;
  msg.max_range_m = static_cast<float>(scan.max_range_m);
  msg.xyz = scan.xyz;
  msg.num_coords = static_cast<int32_t>(msg.xyz.size());
  return msg;
}

void drain(lcm::LCM& lcm) {
  while (lcm.handleTimeout(0) > 0) {
  }
}

}  // namespace

TEST(MappingNode, MapsGoodScansAndCountsBadOnesWithoutCrashing) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  mmh::ServiceContext map_ctx(lcm, "mmh-mapping", "");
  mmh::ServiceContext test_ctx(lcm, "test", "");
  mmh::MappingNode node(map_ctx, testConfig());
  MapListener listener;
  test_ctx.subscribe(mmh::channels::kLocalMap, &MapListener::onMap, &listener);
  const auto world = mmh::test::smallForest();
  const Vector3d origin(0, 0, 1.2);
  int64_t utime = 1'000'000'000;

  mmh::odometry_t odom{};
  odom.header.utime = utime;
  mmh::fromVec3(origin, odom.position);
  odom.orientation[0] = 1.0;
  test_ctx.publish(mmh::channels::kOdometry, odom);
  auto good = cloudOf(mmh::test::scanOf(world, origin, 0.0), utime += 66'667);
  test_ctx.publish(mmh::channels::kPointcloud, good);
  drain(lcm);
  ASSERT_EQ(listener.maps.size(), 1u);
  EXPECT_EQ(listener.maps[0].kind, mmh::local_map_t::KIND_KEYFRAME);
  EXPECT_EQ(listener.results[0], mmh::LocalMapReceiver::Result::kApplied);

  // NaN points among good ones: dropped and counted, the rest is mapped.
  auto with_nan = cloudOf(mmh::test::scanOf(world, origin, 30.0), utime += 66'667);
  for (int i = 0; i < 100; ++i) with_nan.xyz[3 * i * 7] = std::numeric_limits<float>::quiet_NaN();
  test_ctx.publish(mmh::channels::kPointcloud, with_nan);
  // An empty scan, a two-million-point scan, a scan with a NaN pose.
  auto empty = cloudOf(mmh::sim::Scan{}, utime += 66'667);
  empty.max_range_m = 4.5f;
  test_ctx.publish(mmh::channels::kPointcloud, empty);
  auto huge = good;
  huge.header.utime = (utime += 66'667);
  huge.xyz.assign(3 * 2'000'000, 1.0f);
  huge.num_coords = static_cast<int32_t>(huge.xyz.size());
  test_ctx.publish(mmh::channels::kPointcloud, huge);
  auto bad_pose = good;
  bad_pose.header.utime = (utime += 66'667);
  bad_pose.sensor_position[1] = std::numeric_limits<double>::quiet_NaN();
  test_ctx.publish(mmh::channels::kPointcloud, bad_pose);
  // And a good scan after all of that.
  auto after = cloudOf(mmh::test::scanOf(world, origin, 60.0), utime += 66'667);
  test_ctx.publish(mmh::channels::kPointcloud, after);
  drain(lcm);

  EXPECT_EQ(map_ctx.counter("points_nonfinite"), 100);
  EXPECT_EQ(map_ctx.counter("scan_empty"), 1);
  EXPECT_EQ(map_ctx.counter("scan_too_large"), 1);
  EXPECT_EQ(map_ctx.counter("rejected_invalid"), 1);  // NaN pose: refused by validation
  EXPECT_EQ(map_ctx.counter("scans_inserted"), 3);
  ASSERT_EQ(listener.maps.size(), 3u);  // good, with_nan, after
  EXPECT_EQ(listener.maps[1].kind, mmh::local_map_t::KIND_DELTA);
  for (auto r : listener.results) EXPECT_EQ(r, mmh::LocalMapReceiver::Result::kApplied);
  EXPECT_EQ(listener.receiver.grid().rawCells(), node.mapper().map().windowStates());
  // The heartbeat carries the counters.
  map_ctx.publishHeartbeat();
}
