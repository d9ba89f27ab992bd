#include "mmh/mapping/scan_filter.hpp"

#include <pcl/filters/voxel_grid.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cmath>

namespace mmh::mapping {
namespace {

void downsample(pcl::PointCloud<pcl::PointXYZ>::Ptr cloud, double leaf,
                std::vector<Eigen::Vector3f>* out) {
  out->clear();
  if (cloud->empty()) return;
  pcl::VoxelGrid<pcl::PointXYZ> grid;
  const float l = static_cast<float>(leaf);
  grid.setLeafSize(l, l, l);
  grid.setInputCloud(cloud);
  // Kept between calls: no allocation per scan (the service is single-threaded).
  thread_local pcl::PointCloud<pcl::PointXYZ> result;
  grid.filter(result);
  out->reserve(result.size());
  for (const auto& p : result) out->emplace_back(p.x, p.y, p.z);
}

}  // namespace

const char* counterName(ScanError error) {
  switch (error) {
    case ScanError::kNone:
      return "scan_ok";
    case ScanError::kBadPose:
      return "scan_bad_pose";
    case ScanError::kBadRange:
      return "scan_bad_range";
    case ScanError::kEmpty:
      return "scan_empty";
    case ScanError::kTooLarge:
      return "scan_too_large";
    case ScanError::kNoFinitePoint:
      return "scan_no_finite_point";
  }
  return "scan_error";
}

ScanError filterScan(const ScanInput& scan, const MappingParams& params, FilteredScan* out,
                     FilterStats* stats, std::string* reason) {
  *stats = FilterStats{};
  stats->points = scan.num_points;
  out->returns.clear();
  out->free_ends.clear();
  auto fail = [&](ScanError error, const std::string& why) {
    if (reason) *reason = why;
    return error;
  };
  if (!scan.sensor_position.allFinite())
    return fail(ScanError::kBadPose, "sensor pose is not finite");
  if (!std::isfinite(scan.max_range_m) || scan.max_range_m <= 0.0)
    return fail(ScanError::kBadRange, "max_range_m is not a positive number");
  if (scan.num_points == 0 || scan.xyz == nullptr)
    return fail(ScanError::kEmpty, "empty scan (no point)");
  if (scan.num_points > static_cast<size_t>(params.max_points)) {
    return fail(ScanError::kTooLarge,
                "scan has " + std::to_string(scan.num_points) +
                    " points, more than mapping.max_points = " + std::to_string(params.max_points));
  }
  const Eigen::Vector3f origin = scan.sensor_position.cast<float>();
  const double range = std::min(scan.max_range_m, params.max_range_m);
  out->origin = scan.sensor_position;
  out->range_m = range;
  // Scratch clouds kept between scans (no allocation per scan).
  thread_local pcl::PointCloud<pcl::PointXYZ>::Ptr hits(new pcl::PointCloud<pcl::PointXYZ>);
  thread_local pcl::PointCloud<pcl::PointXYZ>::Ptr ends(new pcl::PointCloud<pcl::PointXYZ>);
  hits->clear();
  ends->clear();
  hits->reserve(scan.num_points);
  ends->reserve(scan.num_points);
  const double no_return_beyond = scan.max_range_m + kNoReturnTolerance_m;
  for (size_t i = 0; i < scan.num_points; ++i) {
    const Eigen::Vector3f p(scan.xyz[3 * i], scan.xyz[3 * i + 1], scan.xyz[3 * i + 2]);
    if (!p.allFinite()) {
      ++stats->nonfinite;
      continue;
    }
    const Eigen::Vector3f d = p - origin;
    const double dist = d.norm();
    if (dist < 1e-6) continue;  // no direction: nothing to insert
    if (dist > no_return_beyond || dist > range) {
      // A ray that saw nothing up to `range` (no return, or a return cropped away).
      if (dist > no_return_beyond)
        ++stats->no_return;
      else
        ++stats->cropped;
      const Eigen::Vector3f e = origin + d * static_cast<float>(range / dist);
      ends->push_back(pcl::PointXYZ(e.x(), e.y(), e.z()));
    } else {
      ++stats->returns;
      hits->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
    }
  }
  if (stats->nonfinite == scan.num_points)
    return fail(ScanError::kNoFinitePoint, "no finite point in the scan");
  downsample(hits, params.resolution_m, &out->returns);
  downsample(ends, params.resolution_m, &out->free_ends);
  stats->returns_kept = out->returns.size();
  stats->free_kept = out->free_ends.size();
  return ScanError::kNone;
}

}  // namespace mmh::mapping
