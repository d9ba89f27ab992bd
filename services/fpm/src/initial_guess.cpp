#include "mmh/fpm/initial_guess.hpp"

#include <algorithm>
#include <cmath>

#include "mmh/fpm/speed_profile.hpp"

namespace mmh::fpm {
namespace {

// The path start -> waypoints -> target by arc length, extended straight beyond both ends.
struct Polyline {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> cum;  // arc length at each point

  int segmentAt(double s) const {
    int i = 0;
    while (i + 2 < static_cast<int>(points.size()) && s > cum[i + 1]) ++i;
    return i;
  }
  Eigen::Vector3d direction(int i) const {
    const Eigen::Vector3d d = points[i + 1] - points[i];
    return d.norm() > 1e-12 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d::UnitX();
  }
  Eigen::Vector3d pointAt(double s) const {
    const int i = segmentAt(s);
    return points[i] + direction(i) * (s - cum[i]);
  }
};

// The guess for a start without acceleration.
InitialGuess guessFromSteadyStart(const KinematicState& start, const Eigen::Vector3d& target,
                                  const std::vector<Eigen::Vector3d>& waypoints,
                                  const GuessOptions& options) {
  Polyline path;
  path.points.push_back(start.position);
  // With waypoints a sideways start velocity is not braked beside the path (the offset would
  // still be there at the first waypoint): the path first runs straight on to where braking
  // stops, a corner like the waypoints' but free to move.
  int free_corner = -1;
  if (!waypoints.empty()) {
    const Eigen::Vector3d first = waypoints.front() - start.position;
    const Eigen::Vector3d v = start.velocity;
    if (first.norm() > 1e-9 && (v - first.normalized() * v.dot(first.normalized())).norm() > 1e-6) {
      // (A little further than the braking distance: the smoothing lags by up to a ramp.)
      path.points.push_back(start.position +
                            v * (v.norm() / (1.8 * options.a_max) + options.ramp_s));
      free_corner = 1;
    }
  }
  for (const Eigen::Vector3d& w : waypoints) path.points.push_back(w);
  path.points.push_back(target);
  path.cum.push_back(0.0);
  for (size_t i = 1; i < path.points.size(); ++i)
    path.cum.push_back(path.cum.back() + (path.points[i] - path.points[i - 1]).norm());
  const double length = path.cum.back();

  // At a waypoint where the path turns the guess stops (the velocity turns at rest, so the guess
  // stays inside the limits); the optimiser then rounds the corner as far as the limits allow.
  std::vector<std::pair<double, double>> caps;
  for (size_t i = 1; i + 1 < path.points.size(); ++i) {
    const double cos_turn = path.direction(static_cast<int>(i) - 1).dot(path.direction(i));
    caps.emplace_back(path.cum[i], cos_turn > std::cos(1e-3) ? options.v_max : 0.0);
  }

  // Split the start velocity into a part along the first segment and a sideways part.
  const Eigen::Vector3d dir0 = path.direction(0);
  const double u0 = start.velocity.dot(dir0);
  const Eigen::Vector3d side_v = start.velocity - u0 * dir0;
  const double w0 = side_v.norm();
  const bool sideways = w0 > 1e-6;
  const Eigen::Vector3d side_dir =
      sideways ? Eigen::Vector3d(side_v / w0) : Eigen::Vector3d::Zero();
  // Share the limits between the two motions, which overlap: with |a_side|^2 + |a_along|^2 and
  // the sideways return speed^2 + the speed along the path^2 within the limits, so is their sum.
  // (A moving average keeps both: the norm of an average is at most the average of the norms.)
  // The sideways return is short (the braking distance), so its speed can stay low.
  const double share = sideways ? std::clamp(w0 / options.v_max, 0.1, 0.7) : 0.0;
  const double a_side = options.a_max * share;
  const double a_along = options.a_max * std::sqrt(1.0 - share * share);
  const double v_side = std::min(0.35 * options.v_max, w0 / std::sqrt(2.0));
  const double v_along = std::sqrt(options.v_max * options.v_max - v_side * v_side);

  ProfileSpec along_spec;
  along_spec.length = length;
  along_spec.u0 = u0;
  along_spec.v_max = v_along;
  along_spec.a_max = a_along;
  along_spec.caps = caps;
  if (sideways) {
    // While the sideways speed is braked, the speed along the path stays low enough that the
    // two together stay within the limit.
    along_spec.early_time = w0 / a_side + options.ramp_s;
    along_spec.early_v_max = std::sqrt(std::max(0.0, options.v_max * options.v_max - w0 * w0));
  }
  const SmoothProfile along = SmoothProfile::restToTarget(along_spec, options.ramp_s);
  SmoothProfile side;
  if (sideways) {
    ProfileSpec side_spec;
    side_spec.u0 = w0;
    side_spec.v_max = v_side;
    side_spec.a_max = a_side;
    side = SmoothProfile::restToTarget(side_spec, options.ramp_s);
  }
  const double total = std::max(along.duration(), sideways ? side.duration() : 0.0);

  // Knot times: every kink of both profiles, long stretches split, waypoint passages fixed.
  struct Cut {
    double t;
    int waypoint;  // index into path.points, or -1
  };
  std::vector<Cut> cuts;
  for (double t : along.kinks()) cuts.push_back({t, -1});
  if (sideways)
    for (double t : side.kinks()) cuts.push_back({t, -1});
  for (size_t i = 1; i + 1 < path.points.size(); ++i)
    cuts.push_back({along.timeAt(path.cum[i]), static_cast<int>(i)});
  std::sort(cuts.begin(), cuts.end(), [](const Cut& a, const Cut& b) { return a.t < b.t; });
  std::vector<Cut> kept;
  double prev = 0.0;
  for (const Cut& c : cuts) {
    if (c.waypoint < 0 && (c.t - prev < options.min_piece_s || total - c.t < options.min_piece_s))
      continue;
    if (c.waypoint >= 0 && !kept.empty() && kept.back().waypoint < 0 &&
        c.t - kept.back().t < options.min_piece_s) {
      kept.pop_back();  // a waypoint replaces a free knot right before it
      prev = kept.empty() ? 0.0 : kept.back().t;
    }
    // Split long stretches before this knot.
    const int n = std::max(1, static_cast<int>(std::ceil((c.t - prev) / options.max_piece_s)));
    for (int j = 1; j < n; ++j) kept.push_back({prev + (c.t - prev) * j / n, -1});
    kept.push_back(c);
    prev = c.t;
  }
  const int n_end = std::max(1, static_cast<int>(std::ceil((total - prev) / options.max_piece_s)));
  for (int j = 1; j < n_end; ++j) kept.push_back({prev + (total - prev) * j / n_end, -1});

  InitialGuess g;
  g.profile_duration = along.trapezoid().duration();
  KnotState first;
  first.p = start.position;
  first.v = start.velocity;
  first.a = start.acceleration;
  g.knots.push_back(first);
  for (const Cut& c : kept) {
    const ProfileState s = along.state(c.t);
    const ProfileState l = sideways ? side.state(c.t) : ProfileState{};
    const int seg = path.segmentAt(s.s);
    const Eigen::Vector3d d = path.direction(seg);
    KnotState k;
    k.p = path.pointAt(s.s) + side_dir * l.s;
    k.v = d * s.v + side_dir * l.v;
    k.a = d * s.a + side_dir * l.a;
    if (c.waypoint >= 0 && c.waypoint == free_corner) {
      k.p = path.points[c.waypoint];
      k.v = path.direction(c.waypoint) * s.v;
      k.a = path.direction(c.waypoint) * s.a;
    } else if (c.waypoint >= 0) {
      // On the corner itself: moving (slowly, the profile stops there) along the bisector of the
      // two segments, accelerating along the one the profile is on.
      const Eigen::Vector3d in = path.direction(c.waypoint - 1), out = path.direction(c.waypoint);
      const Eigen::Vector3d bisector = in + out;
      k.p = path.points[c.waypoint];
      k.v = (bisector.norm() > 1e-6 ? Eigen::Vector3d(bisector.normalized()) : out) * s.v +
            side_dir * l.v;
      k.a = (s.a >= 0.0 ? out : in) * s.a + side_dir * l.a;
    }
    g.knots.push_back(k);
    g.fixed.push_back(c.waypoint >= 0 && c.waypoint != free_corner);
  }
  KnotState last;
  last.p = target;
  g.knots.push_back(last);
  g.durations.resize(static_cast<int>(g.knots.size()) - 1);
  double t_prev = 0.0;
  for (size_t i = 0; i < kept.size(); ++i) {
    g.durations[i] = std::max(kept[i].t - t_prev, 0.5 * options.min_piece_s);
    t_prev = kept[i].t;
  }
  g.durations[g.durations.size() - 1] = std::max(total - t_prev, 0.5 * options.min_piece_s);
  return g;
}

}  // namespace

InitialGuess makeInitialGuess(const KinematicState& start, const Eigen::Vector3d& target,
                              const std::vector<Eigen::Vector3d>& waypoints,
                              const GuessOptions& options) {
  const double a0 = start.acceleration.norm();
  if (a0 < 1e-6) return guessFromSteadyStart(start, target, waypoints, options);
  // Let the start acceleration fade out first (jerk as in the ramps), then plan from the state
  // reached. Near the speed limit the fade keeps its length, and its end velocity keeps the
  // direction it turns to but not more than the limit's speed: a fade shortened until it adds
  // no speed ends a turn at v_max in a jerk no airframe follows.
  const double jerk = options.a_max / options.ramp_s;
  const double fade = std::max(a0 / jerk, 0.005);
  const double speed_cap = std::max(start.velocity.norm(), options.v_max);
  KinematicState steady;
  steady.velocity = start.velocity + 0.5 * fade * start.acceleration;
  const double end_speed = steady.velocity.norm();
  if (end_speed > speed_cap) steady.velocity *= speed_cap / end_speed;
  steady.position = start.position + 0.5 * fade * (start.velocity + steady.velocity) +
                    fade * fade / 12.0 * start.acceleration;
  InitialGuess rest = guessFromSteadyStart(steady, target, waypoints, options);
  InitialGuess g;
  KnotState first;
  first.p = start.position;
  first.v = start.velocity;
  first.a = start.acceleration;
  g.knots.push_back(first);
  g.knots.insert(g.knots.end(), rest.knots.begin(), rest.knots.end());
  g.fixed.push_back(false);
  g.fixed.insert(g.fixed.end(), rest.fixed.begin(), rest.fixed.end());
  g.durations.resize(rest.durations.size() + 1);
  g.durations << fade, rest.durations;
  g.profile_duration = rest.profile_duration + fade;
  return g;
}

}  // namespace mmh::fpm
