// The time warp with which EAM slows a curve down: new time t -> old time tau(t). Its rate tau'
// blends smoothly from 1 (the start state is kept: tau' = 1, tau'' = 0 at t = 0) down to 1/k,
// holds 1/k until old time tau_end, and blends back up to 1 after it, so that only the stretch
// that broke the limits (and the way to it) is flown slower and the rest keeps its pace. With
// tau_end infinite the whole rest is slowed by k. Each blend changes the rate as a smoothstep;
// its tangential acceleration peaks at 1.5 |v| (1 - 1/k) / blend.
#pragma once

#include <limits>

namespace mmh::eam {

class TimeWarp {
 public:
  TimeWarp() = default;  // the identity
  TimeWarp(double k, double blend_s, double tau_end_s = std::numeric_limits<double>::infinity(),
           double blend_back_s = 0.0);

  // Old time at new time t, with the rate tau' and its derivative tau''.
  double tau(double t, double* rate, double* rate_dot) const;
  // New time at which the old time reaches old_duration_s.
  double newDuration(double old_duration_s) const;
  // Old time at which the rate is back to 1 (infinite when the rest stays slowed).
  double tauRestored() const { return tau_restored_; }
  double factor() const { return k_; }

 private:
  // New time in [lo, hi] at which tau reaches old_time_s (a blend, where tau has no simple
  // inverse).
  double inverseWithin(double lo, double hi, double old_time_s) const;

  double k_ = 1.0, drop_ = 0.0;
  double blend_ = 0.0;                                         // new time of the first blend
  double hold_end_ = std::numeric_limits<double>::infinity();  // new time the blend back starts
  double blend_back_ = 0.0;
  double tau_blend_ = 0.0, tau_hold_end_ = 0.0;
  double tau_restored_ = std::numeric_limits<double>::infinity();
};

}  // namespace mmh::eam
