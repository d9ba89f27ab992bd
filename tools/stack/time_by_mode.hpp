// Where a flight's time and energy go: the time flown on each mode's trajectory, the time lost on
// it against flying at v_max (the integral of 1 - speed / v_max) and the energy (integral of
// |jerk|^2) flown on it, from the flown path's samples. Summed over the modes, the loss is about
// the flight time minus the path length over v_max; it includes the start's acceleration and the
// braking at the goal (about v_max / a_max together). The energies add up to the flight's.
#pragma once

#include <array>
#include <vector>

#include "stack.hpp"

namespace mmh {

// Indexed like plan_request_t.MODE_*: 0 none (before the first commit), FPM, SOM, EAM, stop.
constexpr int kModeSlots = 5;
struct TimeByMode {
  std::array<double, kModeSlots> time_s{};  // flown on each mode
  std::array<double, kModeSlots> lost_s{};  // lost against v_max on each mode
  std::array<double, kModeSlots> energy{};  // integral of |jerk|^2 flown on each mode (m^2/s^5)
};

// Each sample's mode and speed hold until the next sample; the energy flown between two samples
// counts for the later one's mode (a trajectory's jerk comes right after its commit, within the
// step that switched to it). A mode outside 0..4 counts as none.
TimeByMode timeByMode(const std::vector<PathSample>& path, double max_vel_mps);

}  // namespace mmh
