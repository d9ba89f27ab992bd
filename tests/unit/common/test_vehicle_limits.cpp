// The rest-to-rest time bound of docs/benchmark.md, against its closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "mmh/common/vehicle_limits.hpp"

TEST(TimeBound, ObstacleFreeProtocolFlightIs14_8s) {
  EXPECT_NEAR(mmh::restToRestTime(39.9, 3.0, 2.0), 39.9 / 3.0 + 1.5, 1e-12);
  EXPECT_NEAR(mmh::restToRestTime(39.9, 3.0, 2.0), 14.8, 1e-12);
  // Too short to reach v_max: accelerate half way, brake half way.
  EXPECT_NEAR(mmh::restToRestTime(2.0, 3.0, 2.0), 2.0 * std::sqrt(1.0), 1e-12);
  // Continuous at the switch (length = v^2 / a = 4.5 m).
  EXPECT_NEAR(mmh::restToRestTime(4.5, 3.0, 2.0), 3.0, 1e-12);
  EXPECT_LT(mmh::restToRestTime(-1.0, 3.0, 2.0), 0.0);
}
