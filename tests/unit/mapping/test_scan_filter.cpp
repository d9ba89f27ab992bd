// Scan filtering: NaN/Inf points, returns vs no-return rays, cropping, downsampling, bad scans.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mmh/mapping/scan_filter.hpp"

using Eigen::Vector3d;
using mmh::mapping::FilteredScan;
using mmh::mapping::FilterStats;
using mmh::mapping::ScanError;
using mmh::mapping::ScanInput;

namespace {

ScanInput input(const std::vector<float>& xyz, double range = 4.5) {
  ScanInput in;
  in.sensor_position = Vector3d(0, 0, 1);
  in.max_range_m = range;
  in.xyz = xyz.data();
  in.num_points = xyz.size() / 3;
  return in;
}

}  // namespace

TEST(ScanFilter, SplitsReturnsAndNoReturnRaysAndDropsNaN) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<float> xyz = {
      2.0f,  0.0f, 1.0f,  // return at 2 m
      2.01f, 0.0f, 1.0f,  // same voxel: downsampled into one
      0.0f,  4.5f, 1.0f,  // return exactly at the range
      0.0f,  5.5f, 1.0f,  // no-return ray (range + 1 m)
      nan,   0.0f, 1.0f, inf, 1.0f, 1.0f,
  };
  mmh::mapping::MappingParams params;
  FilteredScan out;
  FilterStats stats;
  std::string reason;
  ASSERT_EQ(mmh::mapping::filterScan(input(xyz), params, &out, &stats, &reason), ScanError::kNone);
  EXPECT_EQ(stats.points, 6u);
  EXPECT_EQ(stats.nonfinite, 2u);
  EXPECT_EQ(stats.returns, 3u);
  EXPECT_EQ(stats.no_return, 1u);
  EXPECT_EQ(out.returns.size(), 2u);
  ASSERT_EQ(out.free_ends.size(), 1u);
  // The free ray ends at the range, not at the placeholder point.
  EXPECT_NEAR((out.free_ends[0].cast<double>() - Vector3d(0, 0, 1)).norm(), 4.5, 1e-5);
  EXPECT_DOUBLE_EQ(out.range_m, 4.5);
}

TEST(ScanFilter, CropsReturnsBeyondTheMappingRange) {
  mmh::mapping::MappingParams params;
  params.max_range_m = 3.0;
  const std::vector<float> xyz = {2.0f, 0.0f, 1.0f, 4.0f, 0.0f, 1.0f};
  FilteredScan out;
  FilterStats stats;
  ASSERT_EQ(mmh::mapping::filterScan(input(xyz), params, &out, &stats, nullptr), ScanError::kNone);
  EXPECT_EQ(stats.returns, 1u);
  EXPECT_EQ(stats.cropped, 1u);
  ASSERT_EQ(out.free_ends.size(), 1u);
  EXPECT_NEAR(out.free_ends[0].x(), 3.0, 1e-5);  // free up to 3 m, no obstacle there
}

TEST(ScanFilter, UnusableScansGiveAReason) {
  mmh::mapping::MappingParams params;
  FilteredScan out;
  FilterStats stats;
  std::string reason;
  const std::vector<float> one = {1.0f, 0.0f, 1.0f};
  ScanInput in = input(one);
  in.sensor_position.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(mmh::mapping::filterScan(in, params, &out, &stats, &reason), ScanError::kBadPose);
  EXPECT_NE(reason.find("pose"), std::string::npos);
  in = input(one, std::numeric_limits<double>::infinity());
  EXPECT_EQ(mmh::mapping::filterScan(in, params, &out, &stats, &reason), ScanError::kBadRange);
  const std::vector<float> none;
  EXPECT_EQ(mmh::mapping::filterScan(input(none), params, &out, &stats, &reason),
            ScanError::kEmpty);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> all_nan = {nan, nan, nan, nan, 1.0f, 1.0f};
  EXPECT_EQ(mmh::mapping::filterScan(input(all_nan), params, &out, &stats, &reason),
            ScanError::kNoFinitePoint);
  EXPECT_EQ(stats.nonfinite, 2u);
  // Two million points: over the cap, refused before any work.
  const std::vector<float> huge(3 * 2'000'000, 1.0f);
  EXPECT_EQ(mmh::mapping::filterScan(input(huge), params, &out, &stats, &reason),
            ScanError::kTooLarge);
  EXPECT_NE(reason.find("mapping.max_points"), std::string::npos);
  EXPECT_STREQ(mmh::mapping::counterName(ScanError::kTooLarge), "scan_too_large");
}
