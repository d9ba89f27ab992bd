#include "mapping_node.hpp"

#include "mmh/common/msg_convert.hpp"

namespace mmh {

local_map_t toLocalMap(const mapping::MapUpdate& update) {
  local_map_t msg{};
  msg.header.utime = update.utime;
  msg.map_seq = update.map_seq;
  msg.resolution_m = update.resolution_m;
  for (int i = 0; i < 3; ++i) {
    msg.origin_index[i] = update.origin_index[i];
    msg.size[i] = update.size[i];
  }
  msg.kind = update.keyframe ? local_map_t::KIND_KEYFRAME : local_map_t::KIND_DELTA;
  msg.base_seq = update.base_seq;
  msg.runs = encodeRuns(update.cells);
  msg.num_bytes = static_cast<int32_t>(msg.runs.size());
  msg.num_changed = static_cast<int32_t>(update.cells.size());
  return msg;
}

MappingNode::MappingNode(ServiceContext& ctx, const Config& config)
    : ctx_(ctx), mapper_(mapping::loadMappingParams(config)) {
  ctx_.subscribe(channels::kPointcloud, &MappingNode::onPointcloud, this);
  ctx_.subscribe(channels::kOdometry, &MappingNode::onOdometry, this);
}

void MappingNode::onOdometry(const odometry_t& msg) {
  mapper_.setVehiclePosition(toVec3(msg.position));
}

void MappingNode::onPointcloud(const pointcloud_t& msg) {
  const int64_t t0 = wallTimeUs();  // compute time only
  mapping::ScanInput scan;
  scan.sensor_position = toVec3(msg.sensor_position);
  scan.max_range_m = msg.max_range_m;
  scan.xyz = msg.xyz.data();
  scan.num_points = msg.xyz.size() / 3;
  mapping::Mapper::Result r = mapper_.processScan(scan, msg.header.utime);
  if (r.filter.nonfinite > 0) {
    // The points are dropped, the rest of the scan is used: counted, not a rejected message.
    ctx_.increment("points_nonfinite", static_cast<int64_t>(r.filter.nonfinite));
    if (nonfinite_log_.shouldLog()) {
      logWarn(ctx_.service() + ": POINTCLOUD: dropped " + std::to_string(r.filter.nonfinite) +
              " NaN/Inf points of " + std::to_string(r.filter.points) +
              " [points_nonfinite = " + std::to_string(ctx_.counter("points_nonfinite")) + "]");
    }
  }
  if (r.error != mapping::ScanError::kNone) {
    ctx_.reject(mapping::counterName(r.error), "POINTCLOUD rejected: " + r.reason);
    return;
  }
  ctx_.increment("scans_inserted");
  if (r.filter.cropped > 0)
    ctx_.increment("points_cropped", static_cast<int64_t>(r.filter.cropped));
  local_map_t out = toLocalMap(r.map);
  ctx_.publish(channels::kLocalMap, out);
  ctx_.increment(r.map.keyframe ? "keyframes" : "deltas");
  if (r.keyframe_follows) {
    // Built once the delta is out: a newly mapped obstacle does not wait for the whole window.
    local_map_t keyframe = toLocalMap(mapper_.keyframe());
    ctx_.publish(channels::kLocalMap, keyframe);
    ctx_.increment("keyframes");
  }
  mapper_.maintain();
  last_compute_us_ = wallTimeUs() - t0;
  ctx_.increment("compute_us_total", last_compute_us_);
}

}  // namespace mmh
