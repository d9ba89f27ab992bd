// First stage of the mapping: a raw world-frame scan is checked (pose, size), cleaned (NaN/Inf
// points dropped and counted), split into returns and no-return rays (pointcloud_t convention:
// a point beyond max_range_m is a ray that saw nothing), cropped to the mapping range, and both
// sets downsampled with PCL's VoxelGrid to the map resolution (one ray end per voxel).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "mmh/mapping/mapping_params.hpp"

namespace mmh::mapping {

// Distance tolerance for float rounding when telling returns from no-return rays.
constexpr double kNoReturnTolerance_m = 0.01;

struct ScanInput {
  Eigen::Vector3d sensor_position = Eigen::Vector3d::Zero();
  double max_range_m = 0.0;    // sensor range (pointcloud_t.max_range_m)
  const float* xyz = nullptr;  // world-frame points, 3 floats each
  size_t num_points = 0;
};

struct FilteredScan {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double range_m = 0.0;                    // free space is inserted up to this distance
  std::vector<Eigen::Vector3f> returns;    // occupied ray ends (downsampled)
  std::vector<Eigen::Vector3f> free_ends;  // ends of free rays at range_m (downsampled)
};

struct FilterStats {
  size_t points = 0;        // points in the scan
  size_t nonfinite = 0;     // dropped: NaN or Inf coordinates
  size_t returns = 0;       // obstacle returns within range
  size_t no_return = 0;     // rays that saw nothing (beyond the sensor range)
  size_t cropped = 0;       // returns beyond mapping.max_range_m, used as free rays
  size_t returns_kept = 0;  // after downsampling
  size_t free_kept = 0;
};

// Why a scan cannot be used at all.
enum class ScanError { kNone, kBadPose, kBadRange, kEmpty, kTooLarge, kNoFinitePoint };
// HEARTBEAT counter name of an error ("scan_bad_pose", "scan_empty", ...).
const char* counterName(ScanError error);

// kNone, or the error with a reason (and nothing to insert) for an unusable scan: non-finite
// pose or range, no point at all, more than params.max_points points, or no finite point.
ScanError filterScan(const ScanInput& scan, const MappingParams& params, FilteredScan* out,
                     FilterStats* stats, std::string* reason);

}  // namespace mmh::mapping
