#include "mmh/viewer/flown_path.hpp"

#include <cmath>

namespace mmh::viewer {
namespace {
double norm3(const double v[3]) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}
}  // namespace

std::optional<PathSample> FlownPath::add(const odometry_t& msg) {
  const double t = msg.header.utime * 1e-6;
  if (!samples_.empty()) {
    const PathSample& last = samples_.back();
    const double moved[3] = {msg.position[0] - last.position[0], msg.position[1] - last.position[1],
                             msg.position[2] - last.position[2]};
    if (t <= last.t_s) return std::nullopt;
    if (norm3(moved) < spacing_m_ && t - last.t_s < max_interval_s_) return std::nullopt;
  }
  PathSample s;
  s.t_s = t;
  for (int i = 0; i < 3; ++i) s.position[i] = msg.position[i];
  s.speed_mps = norm3(msg.velocity);
  s.acceleration_mps2 = norm3(msg.acceleration);
  samples_.push_back(s);
  if (samples_.size() > max_samples_) samples_.pop_front();
  return s;
}

}  // namespace mmh::viewer
