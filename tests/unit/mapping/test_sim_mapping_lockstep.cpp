// SimNode and MappingNode in one process on memq://, stepped in lock-step as mmh-stack does:
// the map of a short flight matches the forest, and the same seed gives the same LOCAL_MAP
// stream byte for byte.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <cmath>

#include "mapping_node.hpp"
#include "mmh/common/forest.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/common/msg_convert.hpp"
#include "sim_node.hpp"

using Eigen::Vector3d;

namespace {

struct Collector {
  void onMap(const mmh::local_map_t& m) {
    std::vector<uint8_t> bytes(m.getEncodedSize());
    m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    stream.insert(stream.end(), bytes.begin(), bytes.end());
    receiver.apply(m);
    ++maps;
  }
  std::vector<uint8_t> stream;
  mmh::LocalMapReceiver receiver;
  int maps = 0;
};

// The default configuration without sensor range noise: every mapped voxel must touch a trunk.
mmh::Config noiselessDefaultConfig() {
  std::ifstream in(std::string(MMH_SOURCE_DIR) + "/deploy/config/default.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const std::string noisy = "range_noise_m: 0.02", quiet = "range_noise_m: 0.0 ";
  size_t replaced = 0;
  for (size_t at = yaml.find(noisy); at != std::string::npos; at = yaml.find(noisy, at)) {
    yaml.replace(at, noisy.size(), quiet);
    ++replaced;
  }
  EXPECT_EQ(replaced, 2u) << "the default config's sensor noise keys moved";
  return mmh::Config::fromString(yaml, "default.yaml without noise");
}

// Flies 1.2 m forward and back (yaw turns round), returns the collected stream.
Collector fly(const mmh::SimOptions& options) {
  const mmh::Config config = noiselessDefaultConfig();
  lcm::LCM lcm("memq://");
  mmh::ServiceContext sim_ctx(lcm, "mmh-sim", ""), map_ctx(lcm, "mmh-mapping", ""),
      test_ctx(lcm, "test", "");
  mmh::SimNode sim(sim_ctx, config, options);
  mmh::MappingNode mapping(map_ctx, config);
  Collector collector;
  test_ctx.subscribe(mmh::channels::kLocalMap, &Collector::onMap, &collector);
  mmh::Trajectory traj;
  const Vector3d a = options.start, b = options.start + Vector3d(1.2, 0.0, 0.0);
  for (const auto& [from, to] : {std::pair{a, b}, std::pair{b, a}}) {
    mmh::Piece p;
    p.duration = 2.0;
    const Vector3d d = to - from;
    p.coeffs.col(0) = from;
    p.coeffs.col(3) = 10.0 * d / 8.0;
    p.coeffs.col(4) = -15.0 * d / 16.0;
    p.coeffs.col(5) = 6.0 * d / 32.0;
    traj.append(p);
  }
  mmh::trajectory_t msg{};
  msg.header.utime = sim.nowUtime();
  msg.trajectory_id = 1;
  msg.start_utime = sim.nowUtime() + 100'000;
  mmh::toMsg(traj, msg);
  test_ctx.publish(mmh::channels::kTrajectory, msg);
  for (int i = 0; i < 500; ++i) {
    while (lcm.handleTimeout(0) > 0) {
    }
    sim.step();
  }
  while (lcm.handleTimeout(0) > 0) {
  }
  EXPECT_FALSE(sim.metrics().collided);
  return collector;
}

}  // namespace

TEST(SimMappingLockStep, MapMatchesTheForestAndRunsRepeat) {
  mmh::SimOptions options;
  options.density_per_m2 = 0.2;
  options.seed = 9;
  const Collector first = fly(options);
  // 5 s at 15 Hz, both ends included, and the keyframes that follow a delta each second.
  EXPECT_EQ(first.maps, 76 + 4);
  ASSERT_TRUE(first.receiver.hasMap());
  mmh::ForestSpec spec;
  spec.density_per_m2 = options.density_per_m2;
  spec.seed = 9;
  const auto forest = mmh::generateForest(spec);
  const mmh::VoxelGrid& g = first.receiver.grid();
  int64_t occupied = 0, on_surface = 0;
  for (int64_t i = 0; i < g.numCells(); ++i) {
    if (g.atLinear(i) != mmh::Occupancy::kOccupied) continue;
    ++occupied;
    const double d = mmh::distanceToForest(forest, g.centerOfLocal(g.localFromLinear(i)));
    on_surface += std::abs(d) <= 0.1 * std::sqrt(3.0) / 2 + 1e-6;
  }
  EXPECT_GT(occupied, 300);
  EXPECT_EQ(on_surface, occupied);
  // Same options, same stream.
  const Collector second = fly(options);
  EXPECT_EQ(first.stream, second.stream);
}
