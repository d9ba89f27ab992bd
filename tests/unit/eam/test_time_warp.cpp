// EAM's time warp (time_warp.hpp): the old time as a function of the new one, checked against
// its own derivatives by finite differences, at the phase boundaries, and end to end.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mmh/eam/time_warp.hpp"

using mmh::eam::TimeWarp;

namespace {

double tauAt(const TimeWarp& w, double t, double* rate = nullptr, double* rate_dot = nullptr) {
  double r = 0.0, rd = 0.0;
  const double tau = w.tau(t, &r, &rd);
  if (rate) *rate = r;
  if (rate_dot) *rate_dot = rd;
  return tau;
}

// tau' and tau'' agree with finite differences of tau and tau' everywhere on [0, t_end], and
// nothing jumps at the phase boundaries (C2 warp: the re-sampled curve stays smooth).
void expectConsistent(const TimeWarp& w, double t_end) {
  const double h = 1e-5;
  for (double t = h; t < t_end - h; t += 0.01) {
    double r = 0.0, rd = 0.0, r_lo = 0.0, r_hi = 0.0;
    tauAt(w, t, &r, &rd);
    const double lo = tauAt(w, t - h, &r_lo), hi = tauAt(w, t + h, &r_hi);
    ASSERT_NEAR((hi - lo) / (2 * h), r, 1e-6) << "t " << t;
    ASSERT_NEAR((r_hi - r_lo) / (2 * h), rd, 1e-3) << "t " << t;
    ASSERT_GT(r, 0.0);
  }
}

}  // namespace

TEST(TimeWarp, TheDefaultIsTheIdentity) {
  const TimeWarp w;
  for (double t : {0.0, 0.5, 3.0}) EXPECT_DOUBLE_EQ(tauAt(w, t), t);
  EXPECT_DOUBLE_EQ(w.newDuration(4.0), 4.0);
}

TEST(TimeWarp, SlowingTheWholeRestKeepsTheStartAndHoldsOneOverK) {
  const TimeWarp w(2.0, 1.0);
  double rate = 0.0, rate_dot = 0.0;
  EXPECT_DOUBLE_EQ(tauAt(w, 0.0, &rate, &rate_dot), 0.0);
  EXPECT_DOUBLE_EQ(rate, 1.0);  // the start state is kept
  EXPECT_DOUBLE_EQ(rate_dot, 0.0);
  tauAt(w, 5.0, &rate);
  EXPECT_DOUBLE_EQ(rate, 0.5);
  EXPECT_TRUE(std::isinf(w.tauRestored()));
  // tau at the end of the blend: blend (1/k + (1 - 1/k) / 2) = 0.75; then half speed.
  EXPECT_NEAR(w.newDuration(4.0), 1.0 + 2.0 * (4.0 - 0.75), 1e-12);
  expectConsistent(w, 8.0);
}

TEST(TimeWarp, ALocalSlowDownReturnsToThePaceAfterTauEnd) {
  const double k = 1.5, blend = 0.8, tau_end = 2.0, back = 0.6;
  const TimeWarp w(k, blend, tau_end, back);
  expectConsistent(w, 10.0);
  // Slowed until old time tau_end, back to rate 1 from tauRestored on.
  const double t_hold_end = w.newDuration(tau_end);
  double rate = 0.0;
  tauAt(w, t_hold_end - 1e-9, &rate);
  EXPECT_NEAR(rate, 1.0 / k, 1e-6);
  const double t_restored = w.newDuration(w.tauRestored());
  EXPECT_NEAR(t_restored - t_hold_end, back, 1e-9);
  tauAt(w, t_restored + 0.5, &rate);
  EXPECT_DOUBLE_EQ(rate, 1.0);
  // After the return the old curve is flown at its own pace, a constant delay behind it.
  EXPECT_NEAR(w.newDuration(9.0) - w.newDuration(7.0), 2.0, 1e-9);
  EXPECT_GT(w.newDuration(9.0), 9.0);
  // newDuration inverts tau in every phase.
  for (double T : {0.3, 1.0, 2.0, 2.3, 5.0}) EXPECT_NEAR(tauAt(w, w.newDuration(T)), T, 1e-9);
}

TEST(TimeWarp, TheBlendsShedSpeedAtMostAtTheRateTheyAreSizedFor) {
  // Flying at v along the old curve, the warp's own tangential acceleration is v tau''; with a
  // blend of 3 v (1 - 1/k) / a_max it peaks at a_max / 2 (both blends).
  const double v = 3.0, a_max = 2.0, k = 1.8;
  const double blend = 3.0 * v * (1.0 - 1.0 / k) / a_max;
  const TimeWarp w(k, blend, 3.0, blend);
  double peak = 0.0;
  for (double t = 0.0; t < 12.0; t += 0.001) {
    double rate = 0.0, rate_dot = 0.0;
    tauAt(w, t, &rate, &rate_dot);
    peak = std::max(peak, std::abs(v * rate_dot));
  }
  EXPECT_NEAR(peak, a_max / 2.0, 1e-3);
}
