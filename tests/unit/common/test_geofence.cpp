// The box a trajectory from a given start must keep to: the fence, or, for a start a little
// outside it (within the arbiter's tolerance), the fence grown by that tolerance.
#include <gtest/gtest.h>

#include "mmh/common/geofence.hpp"

using Eigen::Vector3d;
using mmh::fenceForStart;
using mmh::Geofence;

namespace {
const Vector3d kMin(-30.0, -30.0, 0.3), kMax(30.0, 30.0, 2.7);
const Geofence kFence{kMin, kMax};
}  // namespace

TEST(Geofence, AStartInsideKeepsTheFence) {
  for (const Vector3d& start : {Vector3d(0, 0, 1.2), Vector3d(30, -30, 2.7), Vector3d(0, 0, 0.3)}) {
    const Geofence box = fenceForStart(kFence, start, 0.05);
    EXPECT_EQ(box.min_m, kMin);
    EXPECT_EQ(box.max_m, kMax);
  }
}

TEST(Geofence, AStartWithinTheToleranceOutsideGrowsTheFenceByIt) {
  for (const Vector3d& start : {Vector3d(0, 0, 2.72), Vector3d(0, 0, 0.26), Vector3d(30.04, 0, 1.2),
                                Vector3d(-30.05, 30.05, 2.75)}) {
    SCOPED_TRACE(start.transpose());
    const Geofence box = fenceForStart(kFence, start, 0.05);
    EXPECT_TRUE(box.min_m.isApprox(kMin - Vector3d::Constant(0.05)));
    EXPECT_TRUE(box.max_m.isApprox(kMax + Vector3d::Constant(0.05)));
    EXPECT_TRUE(mmh::insideGeofence(box, start));
  }
}

TEST(Geofence, AStartFartherOutKeepsTheFence) {
  for (const Vector3d& start : {Vector3d(0, 0, 2.8), Vector3d(0, 0, 0.2), Vector3d(31, 0, 1.2)}) {
    SCOPED_TRACE(start.transpose());
    const Geofence box = fenceForStart(kFence, start, 0.05);
    EXPECT_EQ(box.min_m, kMin);
    EXPECT_EQ(box.max_m, kMax);
  }
  // No tolerance: the fence, wherever the start is.
  const Geofence none = fenceForStart(kFence, Vector3d(0, 0, 2.71), 0.0);
  EXPECT_EQ(none.max_m, kMax);
}
