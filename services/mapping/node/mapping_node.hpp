// mmh-mapping as a message-driven node: POINTCLOUD and ODOMETRY in, LOCAL_MAP out (a keyframe at
// least every mapping.keyframe_period_s, a delta for every other scan). Unusable scans are
// rejected with a logged reason and a HEARTBEAT counter; NaN/Inf points are dropped and counted.
#pragma once

#include <cstdint>

#include "mmh/common/config.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/local_map_t.hpp"
#include "mmh/mapping/mapper.hpp"
#include "mmh/odometry_t.hpp"
#include "mmh/pointcloud_t.hpp"

namespace mmh {

// The LOCAL_MAP message of a map update (header.utime = the scan's time; source and seq are the
// publisher's).
local_map_t toLocalMap(const mapping::MapUpdate& update);

class MappingNode {
 public:
  MappingNode(ServiceContext& ctx, const Config& config);

  const mapping::Mapper& mapper() const { return mapper_; }
  // Wall-clock time of the last scan's processing (filter, insertion, encoding), microseconds.
  int64_t lastComputeUs() const { return last_compute_us_; }

 private:
  void onPointcloud(const pointcloud_t& msg);
  void onOdometry(const odometry_t& msg);

  ServiceContext& ctx_;
  mapping::Mapper mapper_;
  int64_t last_compute_us_ = 0;
  LogLimiter nonfinite_log_;
};

}  // namespace mmh
