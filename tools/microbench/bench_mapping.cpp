// Mapping speed and LOCAL_MAP sizes along a flight through a forest (flight_scans.hpp): every
// scan is filtered, inserted and encoded as the node does. Per-scan wall times are collected and
// reported as p50 / p90 / max, with the message sizes: deltas (the first message of every scan)
// and keyframe scans (until the whole window that follows is encoded) apart.
#include <benchmark/benchmark.h>

#include <time.h>

#include <algorithm>
#include <chrono>

#include "flight_scans.hpp"
#include "mapping_node.hpp"
#include "mmh/common/local_map_codec.hpp"
#include "mmh/mapping/mapper.hpp"

namespace {

// CPU time of this thread: the machine is shared, wall time includes waiting for a core.
double threadCpuMs() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * (v.size() - 1) + 0.5))];
}

void BM_MappingFlight(benchmark::State& state) {
  const double density = state.range(0) / 100.0;
  const auto kind = state.range(1) ? mmh::sim::SensorKind::kLidar : mmh::sim::SensorKind::kDepth;
  const int stride = static_cast<int>(state.range(2));
  mmh::mapping::MappingParams params;
  const mmh::FlightScans& flight = mmh::flightScans(density, kind, stride);
  auto mapper = std::make_unique<mmh::mapping::Mapper>(params);
  std::vector<double> delta_cpu_ms, delta_ms, keyframe_ms, upkeep_cpu_ms, delta_kb, keyframe_kb,
      points, rays, cells, updated, free_cells;
  size_t i = 0;
  int64_t utime = 1'000'000'000;
  for (auto _ : state) {
    if (i == flight.scans.size()) {
      state.PauseTiming();
      mapper = std::make_unique<mmh::mapping::Mapper>(params);
      i = 0;
      state.ResumeTiming();
    }
    const mmh::sim::Scan& scan = flight.scans[i++];
    mmh::mapping::ScanInput in;
    in.sensor_position = scan.position;
    in.max_range_m = scan.max_range_m;
    in.xyz = scan.xyz.data();
    in.num_points = scan.xyz.size() / 3;
    utime += 66'667;  // 15 Hz
    const double c0 = threadCpuMs();
    const auto t0 = std::chrono::steady_clock::now();
    mapper->setVehiclePosition(scan.position);
    const auto result = mapper->processScan(in, utime);
    const mmh::local_map_t msg = mmh::toLocalMap(result.map);  // the node's encoding, timed too
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const double cpu_ms = threadCpuMs() - c0;
    benchmark::DoNotOptimize(msg.runs.data());
    // A keyframe scan: the delta is out (its time is a delta's); the whole window follows.
    const bool keyframe_scan = result.map.keyframe || result.keyframe_follows;
    if (!result.map.keyframe) {
      delta_cpu_ms.push_back(cpu_ms);
      delta_ms.push_back(ms);
      delta_kb.push_back(msg.getEncodedSize() / 1024.0);
    }
    if (keyframe_scan) {
      mmh::local_map_t following;
      if (result.keyframe_follows) following = mmh::toLocalMap(mapper->keyframe());
      const mmh::local_map_t& key = result.keyframe_follows ? following : msg;
      benchmark::DoNotOptimize(key.runs.data());
      keyframe_ms.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      keyframe_kb.push_back(key.getEncodedSize() / 1024.0);
    }
    // After the messages are out, as the node does: no receiver waits for it.
    const double m0 = threadCpuMs();
    mapper->maintain();
    if (keyframe_scan) upkeep_cpu_ms.push_back(threadCpuMs() - m0);
    points.push_back(static_cast<double>(in.num_points));
    rays.push_back(static_cast<double>(result.insert.rays));
    cells.push_back(static_cast<double>(result.insert.cells_free + result.insert.cells_occupied));
    updated.push_back(static_cast<double>(result.insert.cells_updated));
    free_cells.push_back(static_cast<double>(result.insert.cells_free));
  }
  state.counters["points"] = percentile(points, 0.5);
  state.counters["rays"] = percentile(rays, 0.5);
  state.counters["cells"] = percentile(cells, 0.5);
  state.counters["updated"] = percentile(updated, 0.5);
  state.counters["free_cells"] = percentile(free_cells, 0.5);
  state.counters["delta_p50_ms"] = percentile(delta_ms, 0.5);
  state.counters["delta_cpu_p50_ms"] = percentile(delta_cpu_ms, 0.5);
  state.counters["delta_p90_ms"] = percentile(delta_ms, 0.9);
  state.counters["delta_max_ms"] = percentile(delta_ms, 1.0);
  state.counters["key_p50_ms"] = percentile(keyframe_ms, 0.5);
  state.counters["key_max_ms"] = percentile(keyframe_ms, 1.0);
  state.counters["upkeep_cpu_p50_ms"] = percentile(upkeep_cpu_ms, 0.5);
  state.counters["upkeep_cpu_max_ms"] = percentile(upkeep_cpu_ms, 1.0);
  state.counters["delta_p50_KB"] = percentile(delta_kb, 0.5);
  state.counters["delta_max_KB"] = percentile(delta_kb, 1.0);
  state.counters["key_max_KB"] = percentile(keyframe_kb, 1.0);
}
// Args: density x 100, lidar (0 = depth 160 x 120, 1 = LiDAR 360 x 56), sim.free_ray_stride.
BENCHMARK(BM_MappingFlight)
    ->Args({20, 0, 1})
    ->Args({20, 0, 4})
    ->Args({0, 0, 1})
    ->Args({20, 1, 1})
    ->Args({20, 1, 4})
    ->Iterations(600)  // three passes over the ~200-frame flight
    ->Unit(benchmark::kMillisecond);

// What a map receiver (arbiter, awareness, SOM, EAM) spends applying each LOCAL_MAP of the same
// flight, with the planners' inflation: while it applies one, a plan request waits. Keyframes
// (the whole window, decoded into a fresh grid) and deltas apart.
void BM_LocalMapReceive(benchmark::State& state) {
  const mmh::FlightScans& flight =
      mmh::flightScans(state.range(0) / 100.0, mmh::sim::SensorKind::kDepth, 1);
  mmh::mapping::MappingParams params;
  mmh::mapping::Mapper mapper(params);
  std::vector<mmh::local_map_t> messages;
  int64_t utime = 1'000'000'000;
  for (const mmh::sim::Scan& scan : flight.scans) {
    mmh::mapping::ScanInput in;
    in.sensor_position = scan.position;
    in.max_range_m = scan.max_range_m;
    in.xyz = scan.xyz.data();
    in.num_points = scan.xyz.size() / 3;
    utime += 66'667;
    mapper.setVehiclePosition(scan.position);
    // What a receiver that lost the scan's delta applies: the keyframe that follows it.
    const auto result = mapper.processScan(in, utime);
    messages.push_back(mmh::toLocalMap(result.keyframe_follows ? mapper.keyframe() : result.map));
  }
  auto receiver = std::make_unique<mmh::LocalMapReceiver>(0.3);  // map.inflation_m
  std::vector<double> keyframe_ms, delta_ms;
  size_t i = 0;
  for (auto _ : state) {
    if (i == messages.size()) {
      state.PauseTiming();
      receiver = std::make_unique<mmh::LocalMapReceiver>(0.3);
      i = 0;
      state.ResumeTiming();
    }
    const mmh::local_map_t& msg = messages[i++];
    const double c0 = threadCpuMs();
    receiver->apply(msg);
    const double ms = threadCpuMs() - c0;
    (msg.kind == mmh::local_map_t::KIND_KEYFRAME ? keyframe_ms : delta_ms).push_back(ms);
    benchmark::DoNotOptimize(receiver->mapSeq());
  }
  state.counters["key_cpu_p50_ms"] = percentile(keyframe_ms, 0.5);
  state.counters["key_cpu_p90_ms"] = percentile(keyframe_ms, 0.9);
  state.counters["key_cpu_max_ms"] = percentile(keyframe_ms, 1.0);
  state.counters["delta_cpu_p50_ms"] = percentile(delta_ms, 0.5);
  state.counters["delta_cpu_max_ms"] = percentile(delta_ms, 1.0);
}
// Arg: density x 100.
BENCHMARK(BM_LocalMapReceive)->Arg(0)->Arg(20)->Iterations(600)->Unit(benchmark::kMillisecond);

}  // namespace
