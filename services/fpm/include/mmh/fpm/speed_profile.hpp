// One-dimensional speed profiles along a path, used to initialise the FPM optimisation:
//  - SpeedProfile: the fastest piecewise-constant-acceleration profile (the classic trapezoid and
//    its triangle / turn-around variants) from a start speed to rest at a given arc length;
//  - SmoothProfile: that trapezoid under a moving average over a ramp time, which turns every
//    acceleration step into a linear ramp (a jerk-limited "S-curve") without raising speed or
//    acceleration. Its pieces between kinks are cubics, so quintic pieces reproduce it exactly.
#pragma once

#include <utility>
#include <vector>

namespace mmh::fpm {

// A phase of constant acceleration.
struct ProfilePhase {
  double duration = 0.0;
  double accel = 0.0;
  double start_s = 0.0;  // arc length at the phase start
  double start_v = 0.0;  // speed along the path at the phase start (may be negative)
};

// What a profile must do: from arc length 0 at speed u0 (negative: moving backwards) to rest at
// `length`, under |v| <= v_max and |a| <= a_max.
struct ProfileSpec {
  double length = 0.0, u0 = 0.0, v_max = 3.0, a_max = 2.0;
  // Speed caps at arc lengths (corners: at most .second at arc length .first), sorted.
  std::vector<std::pair<double, double>> caps;
  // Until early_time the speed also stays at most early_v_max (0: no such cap); FPM uses it while
  // a sideways start velocity is still being braked.
  double early_time = 0.0, early_v_max = 0.0;
};

class SpeedProfile {
 public:
  // The fastest profile for the spec. If u0 is too fast to stop before `length` (or length < 0),
  // it brakes past the end and comes back.
  static SpeedProfile restToTarget(const ProfileSpec& spec);

  const std::vector<ProfilePhase>& phases() const { return phases_; }
  double duration() const;
  double startSpeed() const { return start_v_; }
  double endPosition() const { return end_s_; }
  double positionAt(double t) const;  // extended: u0 t before the start, at rest after the end
  double speedAt(double t) const;
  // Integral of the extended position from 0 to t.
  double positionIntegral(double t) const;

 private:
  void add(double duration, double accel);
  // Without the early cap.
  static SpeedProfile plain(double length, double u0, double v_max, double a_max,
                            const std::vector<std::pair<double, double>>& caps);
  void append(const SpeedProfile& rest);  // continue with `rest` (planned from this end state)
  // Accelerate from v0 to the highest speed <= v_cap that still reaches v1 over `length`, cruise,
  // then brake/accelerate to v1 (v0, v1 >= 0 and reachable from each other within `length`).
  void addSegment(double length, double v0, double v1, double v_cap, double a);

  std::vector<ProfilePhase> phases_;
  double start_v_ = 0.0;
  double end_s_ = 0.0, end_v_ = 0.0;
};

struct ProfileState {
  double s = 0.0, v = 0.0, a = 0.0;
};

class SmoothProfile {
 public:
  // The spec's trapezoid (starting at zero acceleration) with every acceleration change a linear
  // ramp of `ramp` seconds (ramp > 0). With shape_ends, the first ramp (from the
  // start) and the last ramp (into rest) are quadratic instead: the jerk starts at twice the
  // linear ramp's and falls to zero (resp. rises from zero), which gets going ramp / 6 earlier at
  // each end for a third more jerk energy in that ramp - what the optimiser converges to anyway.
  static SmoothProfile restToTarget(const ProfileSpec& spec, double ramp, bool shape_ends = true);

  double duration() const { return duration_; }
  ProfileState state(double t) const;
  // Times strictly inside (0, duration()) where the jerk changes (or stops being constant).
  std::vector<double> kinks() const;
  // First time at which the arc length reaches s (bisection; the profile is monotone until it
  // first reaches its end).
  double timeAt(double s) const;
  const SpeedProfile& trapezoid() const { return trapezoid_; }

 private:
  // Moving-average profile at its own time t (without the end shaping).
  ProfileState averaged(double t) const;
  void plan(const ProfileSpec& spec, double length);

  SpeedProfile trapezoid_;
  double ramp_ = 0.1;
  double offset_ = 0.0;  // the moving average lags by u0 ramp / 2: added back
  double u0_ = 0.0;
  double duration_ = 0.0;
  double end_s_ = 0.0;
  // Quadratic end ramps: accelerations reached, time saved, position correction of the middle.
  bool shaped_start_ = false, shaped_end_ = false;
  double start_a_ = 0.0, end_a_ = 0.0;
  double start_shift_ = 0.0, start_ds_ = 0.0;
};

}  // namespace mmh::fpm
