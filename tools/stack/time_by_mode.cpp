#include "time_by_mode.hpp"

#include <algorithm>

namespace mmh {

TimeByMode timeByMode(const std::vector<PathSample>& path, double max_vel_mps) {
  TimeByMode out;
  if (!(max_vel_mps > 0.0)) return out;
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const PathSample& s = path[i];
    const double dt = path[i + 1].t - s.t;
    if (!(dt > 0.0)) continue;
    const int mode = (s.mode >= 0 && s.mode < kModeSlots) ? s.mode : 0;
    out.time_s[mode] += dt;
    out.lost_s[mode] += dt * std::max(0.0, 1.0 - s.speed / max_vel_mps);
    // A new trajectory's jerk comes right after its commit: a step's energy counts for the mode
    // flown at its end.
    const int end_mode =
        (path[i + 1].mode >= 0 && path[i + 1].mode < kModeSlots) ? path[i + 1].mode : 0;
    out.energy[end_mode] += std::max(0.0, path[i + 1].energy - s.energy);
  }
  return out;
}

}  // namespace mmh
