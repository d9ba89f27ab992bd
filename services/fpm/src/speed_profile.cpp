#include "mmh/fpm/speed_profile.hpp"

#include <algorithm>
#include <cmath>

#include "mmh/common/vehicle_limits.hpp"

namespace mmh::fpm {

void SpeedProfile::add(double duration, double accel) {
  if (!(duration > 1e-12)) return;
  phases_.push_back(ProfilePhase{duration, accel, end_s_, end_v_});
  end_s_ += end_v_ * duration + 0.5 * accel * duration * duration;
  end_v_ += accel * duration;
}

void SpeedProfile::addSegment(double length, double v0, double v1, double v_cap, double a) {
  // Peak speed of the triangle, capped: v_p^2 = (2 a L + v0^2 + v1^2) / 2.
  const double vp = std::max(
      {std::min(v_cap, std::sqrt(std::max(0.0, a * length + 0.5 * (v0 * v0 + v1 * v1)))), v0, v1});
  const double d_up = (vp * vp - v0 * v0) / (2.0 * a), d_down = (vp * vp - v1 * v1) / (2.0 * a);
  const double cruise = std::max(0.0, length - d_up - d_down);
  add((vp - v0) / a, a);
  if (vp > 1e-9) add(cruise / vp, 0.0);
  add((vp - v1) / a, -a);
}

SpeedProfile SpeedProfile::restToTarget(const ProfileSpec& spec) {
  const SpeedProfile plain_profile = plain(spec.length, spec.u0, spec.v_max, spec.a_max, spec.caps);
  if (!(spec.early_time > 0.0) || !(spec.early_v_max > 0.0) || spec.early_v_max >= spec.v_max)
    return plain_profile;
  // Fly under the early cap; where that profile is still cruising at the cap when the early time
  // is over, continue from there under the full limit.
  const double cap = std::max(spec.early_v_max, std::abs(spec.u0));
  SpeedProfile early = plain(spec.length, spec.u0, cap, spec.a_max, spec.caps);
  double t = 0.0;
  for (size_t i = 0; i < early.phases_.size(); ++i) {
    const ProfilePhase& ph = early.phases_[i];
    if (t + ph.duration > spec.early_time && ph.accel == 0.0 && t < spec.early_time) {
      SpeedProfile head;
      head.start_v_ = early.start_v_;
      head.end_v_ = early.start_v_;
      for (size_t j = 0; j < i; ++j) head.add(early.phases_[j].duration, early.phases_[j].accel);
      head.add(spec.early_time - t, 0.0);
      std::vector<std::pair<double, double>> caps;
      for (const auto& c : spec.caps)
        if (c.first > head.end_s_) caps.emplace_back(c.first - head.end_s_, c.second);
      head.append(plain(spec.length - head.end_s_, head.end_v_, spec.v_max, spec.a_max, caps));
      return head;
    }
    t += ph.duration;
  }
  return early;  // braking starts before the early time is over
}

void SpeedProfile::append(const SpeedProfile& rest) {
  for (const ProfilePhase& ph : rest.phases_) add(ph.duration, ph.accel);
}

SpeedProfile SpeedProfile::plain(double length, double u0, double v_max, double a_max,
                                 const std::vector<std::pair<double, double>>& caps) {
  SpeedProfile p;
  const double a = a_max;
  p.end_v_ = u0;
  p.start_v_ = u0;
  if (u0 < 0.0) {
    // Moving away: stop first (further from the target), then it is a start from rest.
    p.add(-u0 / a, a);
    u0 = 0.0;
  }
  const double remaining = length - p.end_s_;
  const double stop_dist = stoppingDistance(u0, a);
  if (stop_dist >= remaining && caps.empty()) {
    // Too fast to stop in time: brake through the target and come back from beyond it.
    p.add(u0 / a, -a);
    const double back = p.end_s_ - length;  // >= 0
    const double vp = std::min(v_max, std::sqrt(a * back));
    const double cruise = std::max(0.0, back - vp * vp / a);
    p.add(vp / a, -a);
    if (vp > 1e-9) p.add(cruise / vp, 0.0);
    p.add(vp / a, a);
    return p;
  }
  // Anchor speeds: start, caps, end (0); forward and backward passes keep each reachable.
  std::vector<double> s{p.end_s_}, v{std::min(u0, v_max)};
  for (const auto& [at, cap] : caps) {
    if (at <= s.back() + 1e-9 || at >= length - 1e-9) continue;
    s.push_back(at);
    v.push_back(std::clamp(cap, 0.0, v_max));
  }
  s.push_back(length);
  v.push_back(0.0);
  for (size_t i = 1; i < v.size(); ++i)
    v[i] = std::min(v[i], std::sqrt(v[i - 1] * v[i - 1] + 2.0 * a * (s[i] - s[i - 1])));
  for (size_t i = v.size() - 1; i-- > 1;)
    v[i] = std::min(v[i], std::sqrt(v[i + 1] * v[i + 1] + 2.0 * a * (s[i + 1] - s[i])));
  double v0 = u0;
  for (size_t i = 0; i + 1 < s.size(); ++i) {
    const double len = s[i + 1] - s[i];
    if (!(len > 0.0)) continue;
    // Reachable end speed: at most what accelerating allows, at least what braking allows.
    const double v1 = std::clamp(v[i + 1], std::sqrt(std::max(0.0, v0 * v0 - 2.0 * a * len)),
                                 std::sqrt(v0 * v0 + 2.0 * a * len));
    p.addSegment(len, v0, v1, std::max(v_max, v0), a);
    v0 = v1;
  }
  return p;
}

double SpeedProfile::duration() const {
  double t = 0.0;
  for (const ProfilePhase& ph : phases_) t += ph.duration;
  return t;
}

double SpeedProfile::positionAt(double t) const {
  if (t <= 0.0) return start_v_ * t;
  for (const ProfilePhase& ph : phases_) {
    if (t <= ph.duration) return ph.start_s + ph.start_v * t + 0.5 * ph.accel * t * t;
    t -= ph.duration;
  }
  return end_s_;
}

double SpeedProfile::speedAt(double t) const {
  if (t <= 0.0) return start_v_;
  for (const ProfilePhase& ph : phases_) {
    if (t <= ph.duration) return ph.start_v + ph.accel * std::max(0.0, t);
    t -= ph.duration;
  }
  return end_v_;
}

double SpeedProfile::positionIntegral(double t) const {
  if (t <= 0.0) return 0.5 * start_v_ * t * t;  // s(u) = u0 u before the start
  double sum = 0.0;
  for (const ProfilePhase& ph : phases_) {
    const double u = std::min(t, ph.duration);
    sum += ph.start_s * u + 0.5 * ph.start_v * u * u + ph.accel * u * u * u / 6.0;
    t -= ph.duration;
    if (t <= 0.0) return sum;
  }
  return sum + end_s_ * t;
}

void SmoothProfile::plan(const ProfileSpec& spec, double length) {
  // The trailing average starts u0 ramp / 2 behind: plan the trapezoid that much shorter and
  // shift it forward, so that the averaged profile starts at 0 and ends at `length` exactly.
  offset_ = 0.5 * spec.u0 * ramp_;
  ProfileSpec shifted = spec;
  shifted.length = length - offset_;
  for (auto& c : shifted.caps) c.first -= offset_;
  trapezoid_ = SpeedProfile::restToTarget(shifted);
}

SmoothProfile SmoothProfile::restToTarget(const ProfileSpec& spec, double ramp, bool shape_ends) {
  SmoothProfile p;
  const double length = spec.length, u0 = spec.u0;
  p.ramp_ = ramp;
  p.u0_ = u0;
  p.end_s_ = length;
  p.plan(spec, length);
  p.duration_ = p.trapezoid_.duration() + ramp;
  const auto& phases = p.trapezoid_.phases();
  const double shift = ramp / 6.0;
  // A quadratic end ramp needs the neighbouring trapezoid phase to hold its acceleration past
  // the linear ramp (and a middle part to remain).
  const bool can_start = shape_ends && !phases.empty() && phases.front().accel != 0.0 &&
                         phases.front().duration > ramp + shift + 1e-9;
  const bool can_end = shape_ends && phases.size() > 1 && phases.back().accel != 0.0 &&
                       phases.back().duration > ramp + shift + 1e-9;
  if (!can_start && !can_end) return p;
  const auto startOffset = [&](const SmoothProfile& q) {
    // Quadratic ramp from the start: s(ramp) = u0 ramp + a ramp^2 / 4; the average reaches the
    // same speed `shift` later, at this position difference.
    const double a1 = q.trapezoid_.phases().front().accel;
    return q.averaged(ramp + shift).s - (u0 * ramp + 0.25 * a1 * ramp * ramp);
  };
  const auto endOffset = [&](const SmoothProfile& q) {
    // Quadratic ramp into rest at the average's end point L: s(end - ramp) = L + a ramp^2 / 4.
    const double aL = q.trapezoid_.phases().back().accel;
    const double t_ma = q.trapezoid_.duration() + ramp - ramp - shift;
    return q.averaged(t_ma).s - (q.averaged(1e18).s + 0.25 * aL * ramp * ramp);
  };
  // The middle part is the average moved `shift` earlier and down by the start offset; the end
  // ramp must start where it ends up: plan the average for the length that makes both meet.
  double start_ds = can_start ? startOffset(p) : 0.0;
  double end_ds = can_end ? endOffset(p) : 0.0;
  SmoothProfile q = p;
  q.plan(spec, length + start_ds - end_ds);
  const auto& qp = q.trapezoid_.phases();
  if (qp.size() != phases.size() || (can_start && qp.front().duration <= ramp + shift + 1e-9) ||
      (can_end && qp.back().duration <= ramp + shift + 1e-9))
    return p;  // the correction changed the profile's structure: keep the plain average
  q.shaped_start_ = can_start;
  q.shaped_end_ = can_end;
  q.start_a_ = can_start ? qp.front().accel : 0.0;
  q.end_a_ = can_end ? qp.back().accel : 0.0;
  q.start_shift_ = can_start ? shift : 0.0;
  q.start_ds_ = can_start ? startOffset(q) : 0.0;
  q.duration_ = q.trapezoid_.duration() + ramp - q.start_shift_ - (can_end ? shift : 0.0);
  return q;
}

ProfileState SmoothProfile::averaged(double t) const {
  t = std::clamp(t, 0.0, trapezoid_.duration() + ramp_);
  const SpeedProfile& q = trapezoid_;
  ProfileState st;
  st.s = offset_ + (q.positionIntegral(t) - q.positionIntegral(t - ramp_)) / ramp_;
  st.v = (q.positionAt(t) - q.positionAt(t - ramp_)) / ramp_;
  st.a = (q.speedAt(t) - q.speedAt(t - ramp_)) / ramp_;
  return st;
}

ProfileState SmoothProfile::state(double t) const {
  t = std::clamp(t, 0.0, duration_);
  const double r = ramp_;
  if (shaped_start_ && t < r) {
    const double a = start_a_;
    return ProfileState{u0_ * t + a * (t * t * t / (3.0 * r) - t * t * t * t / (12.0 * r * r)),
                        u0_ + a * (t * t / r - t * t * t / (3.0 * r * r)),
                        a * (2.0 * t / r - t * t / (r * r))};
  }
  if (shaped_end_ && t > duration_ - r) {
    const double a = end_a_, x = duration_ - t;  // time to go
    return ProfileState{end_s_ + a * (x * x * x / (3.0 * r) - x * x * x * x / (12.0 * r * r)),
                        -a * (x * x / r - x * x * x / (3.0 * r * r)),
                        a * (2.0 * x / r - x * x / (r * r))};
  }
  ProfileState st = averaged(t + start_shift_);
  st.s -= start_ds_;
  return st;
}

std::vector<double> SmoothProfile::kinks() const {
  std::vector<double> kinks;
  double t = 0.0;
  const auto& phases = trapezoid_.phases();
  for (size_t i = 0; i < phases.size(); ++i) {
    if (i > 0) kinks.push_back(t);
    kinks.push_back(t + ramp_);
    t += phases[i].duration;
  }
  kinks.push_back(t);
  const double lo = shaped_start_ ? ramp_ : 0.0;
  const double hi = shaped_end_ ? duration_ - ramp_ : duration_;
  std::vector<double> inside;
  if (shaped_start_) inside.push_back(ramp_);
  for (double k : kinks) {
    const double at = k - start_shift_;
    if (at > lo + 1e-9 && at < hi - 1e-9) inside.push_back(at);
  }
  if (shaped_end_) inside.push_back(duration_ - ramp_);
  std::sort(inside.begin(), inside.end());
  return inside;
}

double SmoothProfile::timeAt(double s) const {
  double lo = 0.0, hi = duration();
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (state(mid).s < s ? lo : hi) = mid;
  }
  return hi;
}

}  // namespace mmh::fpm
