#include "mmh/eam/time_warp.hpp"

#include <algorithm>
#include <cmath>

namespace mmh::eam {

TimeWarp::TimeWarp(double k, double blend_s, double tau_end_s, double blend_back_s)
    : k_(k), drop_(1.0 - 1.0 / k), blend_(blend_s), blend_back_(blend_back_s) {
  tau_blend_ = blend_ * (1.0 / k_ + 0.5 * drop_);
  if (std::isfinite(tau_end_s)) {
    hold_end_ = blend_ + k_ * std::max(0.0, tau_end_s - tau_blend_);
    tau_hold_end_ = tau_blend_ + (hold_end_ - blend_) / k_;
    tau_restored_ = tau_hold_end_ + blend_back_ * (1.0 / k_ + 0.5 * drop_);
  }
}

double TimeWarp::tau(double t, double* rate, double* rate_dot) const {
  if (t < blend_) {
    const double x = t / blend_;
    *rate = 1.0 / k_ + drop_ * (1.0 - 3.0 * x * x + 2.0 * x * x * x);
    *rate_dot = drop_ * (-6.0 * x + 6.0 * x * x) / blend_;
    return t / k_ + drop_ * blend_ * (x - x * x * x + 0.5 * x * x * x * x);
  }
  if (t < hold_end_) {
    *rate = 1.0 / k_;
    *rate_dot = 0.0;
    return tau_blend_ + (t - blend_) / k_;
  }
  const double s = t - hold_end_;
  if (s < blend_back_) {
    const double x = s / blend_back_;
    *rate = 1.0 / k_ + drop_ * (3.0 * x * x - 2.0 * x * x * x);
    *rate_dot = drop_ * (6.0 * x - 6.0 * x * x) / blend_back_;
    return tau_hold_end_ + s / k_ + drop_ * blend_back_ * (x * x * x - 0.5 * x * x * x * x);
  }
  *rate = 1.0;
  *rate_dot = 0.0;
  return tau_restored_ + (s - blend_back_);
}

double TimeWarp::newDuration(double old_duration_s) const {
  if (old_duration_s >= tau_restored_)
    return hold_end_ + blend_back_ + (old_duration_s - tau_restored_);
  if (old_duration_s <= tau_blend_) return inverseWithin(0.0, blend_, old_duration_s);
  if (old_duration_s <= tau_hold_end_ || !std::isfinite(hold_end_))
    return blend_ + k_ * (old_duration_s - tau_blend_);
  return inverseWithin(hold_end_, hold_end_ + blend_back_, old_duration_s);
}

double TimeWarp::inverseWithin(double lo, double hi, double old_time_s) const {
  // tau increases: bisection (a blend's tau is a quartic, no closed-form inverse worth having).
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    double rate, rate_dot;
    (tau(mid, &rate, &rate_dot) < old_time_s ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace mmh::eam
