// The path the vehicle flew, from ODOMETRY: a sample whenever it moved path_spacing_m or
// max_interval_s passed, with speed and acceleration for the path colours and the plots.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "mmh/odometry_t.hpp"

namespace mmh::viewer {

struct PathSample {
  double t_s = 0.0;  // message clock
  double position[3] = {0.0, 0.0, 0.0};
  double speed_mps = 0.0;
  double acceleration_mps2 = 0.0;
};

class FlownPath {
 public:
  FlownPath(double spacing_m, double max_interval_s, size_t max_samples)
      : spacing_m_(spacing_m), max_interval_s_(max_interval_s), max_samples_(max_samples) {}

  // The new sample if this odometry makes one.
  std::optional<PathSample> add(const odometry_t& msg);
  const std::deque<PathSample>& samples() const { return samples_; }

 private:
  double spacing_m_, max_interval_s_;
  size_t max_samples_;
  std::deque<PathSample> samples_;
};

}  // namespace mmh::viewer
