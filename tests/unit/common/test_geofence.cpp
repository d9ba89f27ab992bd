// The box a trajectory from a given start must keep to: the fence, or, for a start a little
// outside it (within the arbiter's tolerance), the fence grown by that tolerance.
#include <gtest/gtest.h>

#include "mmh/common/geofence.hpp"

using Eigen::Vector3d;
using mmh::Box;
using mmh::fenceForStart;

namespace {
const Vector3d kMin(-30.0, -30.0, 0.3), kMax(30.0, 30.0, 2.7);
}  // namespace

TEST(Geofence, AStartInsideKeepsTheFence) {
  for (const Vector3d& start : {Vector3d(0, 0, 1.2), Vector3d(30, -30, 2.7), Vector3d(0, 0, 0.3)}) {
    const Box box = fenceForStart(kMin, kMax, start, 0.05);
    EXPECT_EQ(box.lo, kMin);
    EXPECT_EQ(box.hi, kMax);
  }
}

TEST(Geofence, AStartWithinTheToleranceOutsideGrowsTheFenceByIt) {
  for (const Vector3d& start : {Vector3d(0, 0, 2.72), Vector3d(0, 0, 0.26), Vector3d(30.04, 0, 1.2),
                                Vector3d(-30.05, 30.05, 2.75)}) {
    SCOPED_TRACE(start.transpose());
    const Box box = fenceForStart(kMin, kMax, start, 0.05);
    EXPECT_TRUE(box.lo.isApprox(kMin - Vector3d::Constant(0.05)));
    EXPECT_TRUE(box.hi.isApprox(kMax + Vector3d::Constant(0.05)));
    EXPECT_TRUE(mmh::insideBox(start, box.lo, box.hi));
  }
}

TEST(Geofence, AStartFartherOutKeepsTheFence) {
  for (const Vector3d& start : {Vector3d(0, 0, 2.8), Vector3d(0, 0, 0.2), Vector3d(31, 0, 1.2)}) {
    SCOPED_TRACE(start.transpose());
    const Box box = fenceForStart(kMin, kMax, start, 0.05);
    EXPECT_EQ(box.lo, kMin);
    EXPECT_EQ(box.hi, kMax);
  }
  // No tolerance: the fence, wherever the start is.
  const Box none = fenceForStart(kMin, kMax, Vector3d(0, 0, 2.71), 0.0);
  EXPECT_EQ(none.hi, kMax);
}
