#include <gtest/gtest.h>

#include <cmath>

#include "mmh/common/collision_check.hpp"
#include "mmh/common/minco.hpp"
#include "mmh/common/stopping_trajectory.hpp"

TEST(StoppingTrajectory, BrakesToRestWithinTheLimitsWithoutAJump) {
  for (double speed : {0.5, 1.5, 3.0}) {
    mmh::KinematicState s;
    s.position = Eigen::Vector3d(1, 2, 1.2);
    s.velocity = Eigen::Vector3d(speed * 0.6, speed * 0.8, 0.0);
    s.acceleration = Eigen::Vector3d(0.3, -0.2, 0.0);
    mmh::Trajectory t = mmh::makeStoppingTrajectory(s, 2.0, 3.0);
    EXPECT_LT((t.position(0) - s.position).norm(), 1e-9);
    EXPECT_LT((t.velocity(0) - s.velocity).norm(), 1e-9);
    EXPECT_LT((t.acceleration(0) - s.acceleration).norm(), 1e-9);
    EXPECT_LT(t.velocity(t.duration()).norm(), 1e-6);
    EXPECT_LT(t.acceleration(t.duration()).norm(), 1e-6);
    EXPECT_LE(t.maxAcceleration(), 2.0 + 1e-9);
    // A start acceleration can raise the speed a little before braking takes over.
    EXPECT_LE(t.maxSpeed(), std::max(3.0, speed) + 0.01);
    // Stops along the direction of motion, not much farther than a bang-bang stop would.
    const double bang_bang = speed * speed / (2 * 2.0);
    const Eigen::Vector3d travel = t.position(t.duration()) - s.position;
    EXPECT_GT(travel.dot(s.velocity.normalized()), 0.0);
    EXPECT_LT(travel.norm(), 2.5 * bang_bang + 0.2);
  }
}

TEST(StoppingTrajectory, AtRestItHolds) {
  mmh::KinematicState s;
  s.position = Eigen::Vector3d(1, 2, 3);
  mmh::Trajectory t = mmh::makeStoppingTrajectory(s, 2.0, 3.0);
  EXPECT_TRUE(t.position(0.5).isApprox(s.position));
  EXPECT_LT(t.maxSpeed(), 1e-12);
}

// A start that already brakes at (or, after a tolerated emergency answer, above) a_max: the stop
// keeps at most that acceleration and takes about as long as braking at a_max, not a minute.
TEST(StoppingTrajectory, StartAtOrAboveTheAccelerationLimitStopsPromptly) {
  for (const Eigen::Vector3d& acc :
       {Eigen::Vector3d(-2.0, 0.0, 0.0), Eigen::Vector3d(-2.0, 0.6, 0.0),
        Eigen::Vector3d(-1.2, 1.7, 0.0), Eigen::Vector3d(0.5, 2.0, 0.2)}) {
    mmh::KinematicState s;
    s.position = Eigen::Vector3d(0, 0, 1.2);
    s.velocity = Eigen::Vector3d(3.0, 0.0, 0.0);
    s.acceleration = acc;
    const mmh::Trajectory t = mmh::makeStoppingTrajectory(s, 2.0, 3.0);
    EXPECT_LT((t.acceleration(0) - acc).norm(), 1e-9);
    EXPECT_LT(t.velocity(t.duration()).norm(), 1e-6);
    EXPECT_LE(t.maxAcceleration(), std::max(2.0, acc.norm()) * 1.01) << acc.transpose();
    EXPECT_LT(t.duration(), 4.0 * 3.0 / 2.0 + 2.0) << acc.transpose();
    EXPECT_LT((t.position(t.duration()) - s.position).norm(), 2.5 * 9.0 / 4.0 + 0.5);
  }
}

TEST(StoppingTrajectory, RestoppingAStopInProgressKeepsBraking) {
  mmh::KinematicState s;
  s.position = Eigen::Vector3d(0, 0, 1.2);
  s.velocity = Eigen::Vector3d(3.0, 0.0, 0.0);
  const mmh::Trajectory first = mmh::makeStoppingTrajectory(s, 2.0, 3.0);
  const Eigen::Vector3d end = first.position(first.duration());
  for (double t0 : {0.2, 0.5, 0.9}) {
    const mmh::Trajectory again = mmh::makeStoppingTrajectory(first, t0, 2.0, 3.0);
    const mmh::KinematicState at = first.state(t0);
    EXPECT_LT((again.acceleration(0) - at.acceleration).norm(), 1e-9);
    EXPECT_LE(again.maxAcceleration(), std::max(2.0, at.acceleration.norm()) * 1.01);
    EXPECT_LT(again.duration(), first.duration() - t0 + 3.0);
    // It does not carry the vehicle much past where the first stop ended.
    EXPECT_LT((again.position(again.duration()) - end).norm(), 1.0) << t0;
  }
}

namespace {

// 16 x 14 x 3 m of free space at 0.1 m (x from -2, y from -4), with an optional vertical pillar.
mmh::VoxelGrid gridWithPillar(double x, double y, double radius) {
  mmh::VoxelGrid g(0.1, Eigen::Vector3i(-20, -40, 0), Eigen::Vector3i(160, 140, 30));
  g.setInflationRadius(0.25);
  for (int64_t i = 0; i < g.numCells(); ++i) {
    const Eigen::Vector3d c = g.centerOfLocal(g.localFromLinear(i));
    g.setLinear(i, std::hypot(c.x() - x, c.y() - y) <= radius ? mmh::Occupancy::kOccupied
                                                              : mmh::Occupancy::kFree);
  }
  return g;
}

// A 0.15 m airframe on a 0.1 m grid enters an occupied cell nearer than this to its centre.
constexpr double kTouch = 0.2;

// From (0, 0, 1.2) at 2 m/s along x, bending left to rest at (2, 2.5, 1.2) in 3 s.
mmh::Trajectory bendingPath() {
  mmh::MincoJerk m;
  Eigen::Matrix3d head, tail;
  head << Eigen::Vector3d(0, 0, 1.2), Eigen::Vector3d(2, 0, 0), Eigen::Vector3d::Zero();
  tail << Eigen::Vector3d(2.0, 2.5, 1.2), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero();
  m.setConditions(head, tail, 1);
  m.setParameters(Eigen::Matrix3Xd(3, 0), Eigen::VectorXd::Constant(1, 3.0));
  return m.trajectory();
}

double distanceToSamples(const std::vector<Eigen::Vector3d>& samples, const Eigen::Vector3d& p) {
  double best = INFINITY;
  for (const auto& s : samples) best = std::min(best, (s - p).norm());
  return best;
}

// Along x at a constant speed for 30 m; or, when radius_m > 0, round a circle of that radius.
mmh::Trajectory steadyPath(double speed, double radius_m) {
  const int pieces = 24;
  const double duration = (radius_m > 0.0 ? 4.0 : 30.0 / speed);
  const double w = radius_m > 0.0 ? speed / radius_m : 0.0;
  auto at = [&](double t) {
    return radius_m > 0.0 ? Eigen::Vector3d(radius_m * std::sin(w * t),
                                            radius_m * (1.0 - std::cos(w * t)), 1.2)
                          : Eigen::Vector3d(speed * t, 0.0, 1.2);
  };
  auto vel = [&](double t) {
    return radius_m > 0.0 ? Eigen::Vector3d(speed * std::cos(w * t), speed * std::sin(w * t), 0.0)
                          : Eigen::Vector3d(speed, 0.0, 0.0);
  };
  auto acc = [&](double t) {
    return Eigen::Vector3d(-speed * w * std::sin(w * t), speed * w * std::cos(w * t), 0.0);
  };
  mmh::MincoJerk m;
  Eigen::Matrix3d head, tail;
  head << at(0.0), vel(0.0), acc(0.0);
  tail << at(duration), vel(duration), acc(duration);
  m.setConditions(head, tail, pieces);
  Eigen::Matrix3Xd inner(3, pieces - 1);
  for (int i = 1; i < pieces; ++i) inner.col(i - 1) = at(duration * i / pieces);
  m.setParameters(inner, Eigen::VectorXd::Constant(pieces, duration / pieces));
  return m.trajectory();
}

}  // namespace

// The arbiter's unmapped-space rule counts on a stop about as long as braking at a_max
// (v^2 / 2a): braking along the path builds up within 0.2 s and then brakes at nearly a_max, on
// a straight path and round a bend (whose centripetal acceleration it pays first), on the curve.
TEST(StoppingTrajectory, BrakesAlongThePathNearlyAsShortAsABangBangStop) {
  for (double speed : {1.0, 2.0, 3.0}) {
    for (double radius : {0.0, 9.0, 4.5}) {
      // A bend flown near a_max leaves almost nothing to brake with along it (see below).
      if (radius > 0.0 && speed * speed / radius > 0.75 * 2.0) continue;
      const mmh::Trajectory path = steadyPath(speed, radius);
      const mmh::Trajectory stop = mmh::makeStoppingTrajectory(path, 0.5, 2.0, 3.0);
      const mmh::KinematicState s = path.state(0.5);
      EXPECT_LT((stop.velocity(0) - s.velocity).norm(), 1e-9);
      EXPECT_LT((stop.acceleration(0) - s.acceleration).norm(), 1e-9);
      EXPECT_LT(stop.velocity(stop.duration()).norm(), 1e-6);
      EXPECT_LE(stop.maxAcceleration(), 2.0 * (1.0 + 1e-6));
      // Bang-bang at 0.95 a_max after half the 0.2 s build-up, and 10 cm for the fit; a bend
      // costs more, the more so the more of a_max it takes.
      const double bend_share = radius > 0.0 ? speed * speed / radius / 2.0 : 0.0;
      const double bound =
          (speed * speed / (2.0 * 0.95 * 2.0) + 0.5 * speed * 0.2 + 0.1) * (1.0 + bend_share);
      EXPECT_LT(stop.arcLength(), bound) << speed << " m/s, radius " << radius;
      const std::vector<Eigen::Vector3d> on_path = [&] {
        std::vector<Eigen::Vector3d> out;
        for (double t = 0.5; t <= 0.5 + 2.0 * speed; t += 0.002) out.push_back(path.position(t));
        return out;
      }();
      for (double t = 0.0; t <= stop.duration(); t += 0.02)
        EXPECT_LT(distanceToSamples(on_path, stop.position(t)), 0.03)
            << speed << " m/s, radius " << radius << " at " << t;
    }
  }
}

// Stopped for danger ahead on a path that bends into a pillar: braking along it (which keeps an
// avoidance under way) would end within 15 cm of its occupied cells, so the straight stop is
// taken; with the way clear, the stop along the path.
TEST(StoppingTrajectory, ChoosesTheStopThatKeepsClearOfTheObstacle) {
  const mmh::Trajectory path = bendingPath();
  const mmh::VoxelGrid clear = gridWithPillar(1.15, 0.6, 0.0);
  const mmh::VoxelGrid pillar = gridWithPillar(1.15, 0.6, 0.3);
  const double clearance = 0.25;
  const mmh::Trajectory along = mmh::makeStoppingTrajectory(path, 0.0, 2.0, 3.0);
  ASSERT_LT(mmh::minOccupiedDistance(pillar, along, 1.0), 0.15);

  const mmh::Trajectory chosen =
      mmh::chooseStoppingTrajectory(&pillar, path, 0.0, 2.0, 3.0, clearance, kTouch);
  EXPECT_GE(mmh::minOccupiedDistance(pillar, chosen, 1.0), clearance);
  EXPECT_LT((chosen.position(0) - path.position(0)).norm(), 1e-9);
  EXPECT_LT((chosen.velocity(0) - path.velocity(0)).norm(), 1e-9);
  EXPECT_LT(chosen.velocity(chosen.duration()).norm(), 1e-6);
  EXPECT_LE(chosen.maxAcceleration(), 2.0 + 1e-6);

  const mmh::Trajectory kept =
      mmh::chooseStoppingTrajectory(&clear, path, 0.0, 2.0, 3.0, clearance, kTouch);
  EXPECT_LT((kept.position(kept.duration()) - along.position(along.duration())).norm(), 1e-9);
}

// assessStop searches the occupied cells only where the clearance could still fall; its minimum
// must be the one a search at every sample (1 cm apart) finds, up to the limit asked.
TEST(StoppingTrajectory, AssessedClearanceIsTheMinimumOverEverySample) {
  const mmh::Trajectory path = bendingPath();
  const mmh::Trajectory stop = mmh::makeStoppingTrajectory(path, 0.0, 2.0, 3.0);
  for (const double y : {0.3, 0.45, 0.6, 0.8, 1.0}) {
    for (const double radius : {0.1, 0.3}) {
      const mmh::VoxelGrid pillar = gridWithPillar(1.15, y, radius);
      for (const double limit : {0.35, 1.0}) {
        double every_sample = limit;
        for (double t = 0.0; t <= stop.duration() + 1e-9; t += 0.002) {
          const double tc = std::min(t, stop.duration());
          every_sample = std::min(every_sample,
                                  mmh::occupiedDistance(pillar, stop.position(tc), every_sample));
        }
        SCOPED_TRACE("pillar at y " + std::to_string(y) + ", radius " + std::to_string(radius) +
                     ", limit " + std::to_string(limit));
        EXPECT_NEAR(mmh::assessStop(pillar, stop, limit).clearance_m, every_sample, 2e-3);
      }
    }
  }
}

// A bend flown at a_max (3 m/s round 4.5 m) leaves nothing to brake with along it at first: that
// stop runs on far longer than the straight one, which is taken when the way is as clear - and
// not when a pillar stands where the straight stop would end.
TEST(StoppingTrajectory, TakesTheStraightStopWhenBrakingAlongABendRunsMuchFarther) {
  const mmh::Trajectory path = steadyPath(3.0, 4.5);
  const mmh::Trajectory along = mmh::makeStoppingTrajectory(path, 0.5, 2.0, 3.0);
  const mmh::Trajectory straight = mmh::makeStoppingTrajectory(path.state(0.5), 2.0, 3.0);
  ASSERT_GT(along.arcLength(), 1.3 * straight.arcLength());
  const Eigen::Vector3d straight_end = straight.position(straight.duration());
  const mmh::VoxelGrid clear = gridWithPillar(straight_end.x(), straight_end.y(), 0.0);
  const mmh::VoxelGrid blocked = gridWithPillar(straight_end.x(), straight_end.y(), 0.3);
  ASSERT_GE(mmh::minOccupiedDistance(blocked, along, 1.0), 0.25);
  ASSERT_LT(mmh::assessStop(clear, along, 0.35).unknown_m, 0.05);

  const mmh::Trajectory taken =
      mmh::chooseStoppingTrajectory(&clear, path, 0.5, 2.0, 3.0, 0.25, kTouch);
  EXPECT_LT((taken.position(taken.duration()) - straight_end).norm(), 1e-9);
  const mmh::Trajectory kept =
      mmh::chooseStoppingTrajectory(&blocked, path, 0.5, 2.0, 3.0, 0.25, kTouch);
  EXPECT_LT((kept.position(kept.duration()) - along.position(along.duration())).norm(), 1e-9);
}

// The map knows only a tube around the path ahead (what the camera saw), and one occupied
// cell of a noisy obstacle edge lies 0.2-0.25 m from the stop along the path: inside the check
// margin, not touching the airframe. The straight stop would keep farther from that cell but run
// into unknown space, where anything may stand: the stop along the path is kept.
TEST(StoppingTrajectory, PrefersKnownSpaceToMoreClearanceFromAMarginCell) {
  const mmh::Trajectory path = bendingPath();
  const mmh::Trajectory along = mmh::makeStoppingTrajectory(path, 0.0, 2.0, 3.0);
  const mmh::Trajectory straight = mmh::makeStoppingTrajectory(path.state(0.0), 2.0, 3.0);
  std::vector<Eigen::Vector3d> samples;
  for (double t = 0.0; t <= along.duration(); t += 0.005) samples.push_back(along.position(t));

  double apart = 0.0;  // how far the straight stop leaves the one along the path
  for (double t = 0.0; t <= straight.duration(); t += 0.01)
    apart = std::max(apart, distanceToSamples(samples, straight.position(t)));
  const double kTube = 0.5 * apart;
  mmh::VoxelGrid g(0.1, Eigen::Vector3i(-20, -40, 0), Eigen::Vector3i(160, 80, 30));
  g.setInflationRadius(0.25);
  bool edge_cell_set = false;
  for (int64_t i = 0; i < g.numCells(); ++i) {
    const Eigen::Vector3d c = g.centerOfLocal(g.localFromLinear(i));
    const double d = distanceToSamples(samples, c);
    if (d <= kTube) g.setLinear(i, mmh::Occupancy::kFree);
    // Left of the path (the inside of the bend), away from the straight stop.
    if (!edge_cell_set && d > 0.21 && d < 0.24 && c.y() > 0.3 && std::abs(c.z() - 1.25) < 0.06) {
      g.setLinear(i, mmh::Occupancy::kOccupied);
      edge_cell_set = true;
    }
  }
  ASSERT_TRUE(edge_cell_set);
  const mmh::StopAssessment along_seen = mmh::assessStop(g, along, 0.35);
  const mmh::StopAssessment straight_seen = mmh::assessStop(g, straight, 0.35);
  ASSERT_GE(along_seen.clearance_m, kTouch);
  ASSERT_LT(along_seen.clearance_m, 0.25);
  ASSERT_GT(straight_seen.clearance_m, along_seen.clearance_m);
  ASSERT_LT(along_seen.unknown_m, 0.05);
  // More than the 0.1 m of unknown that counts as none.
  ASSERT_GT(straight_seen.unknown_m, 0.12) << "tube " << kTube;

  const mmh::Trajectory chosen =
      mmh::chooseStoppingTrajectory(&g, path, 0.0, 2.0, 3.0, 0.25, kTouch);
  EXPECT_LT((chosen.position(chosen.duration()) - along.position(along.duration())).norm(), 1e-9);
}

// The order of stops: touching an occupied cell is worst, then unknown space, then clearance.
TEST(StoppingTrajectory, SaferStopOrdersTouchThenUnknownThenClearance) {
  using mmh::saferStop;
  using mmh::StopAssessment;
  const StopAssessment touching{0.15, 0.0}, blind{0.3, 1.0}, known_near{0.21, 0.0},
      known_far{0.3, 0.0};
  EXPECT_TRUE(saferStop(blind, touching, kTouch));
  EXPECT_FALSE(saferStop(touching, blind, kTouch));
  EXPECT_TRUE(saferStop(known_near, blind, kTouch));
  EXPECT_TRUE(saferStop(known_far, known_near, kTouch));
  EXPECT_FALSE(saferStop(known_near, known_far, kTouch));
  EXPECT_TRUE(saferStop(StopAssessment{0.18, 0.0}, touching, kTouch));  // both touch: clearance
}

// Every stop that swerves starts exactly in the given state, ends at rest beside the straight
// stop's end, keeps a_max and v_max, and they come ordered from the least swerve to the most.
TEST(StoppingTrajectory, SwervingStopsEndAtRestBesideTheStraightStopWithinTheLimits) {
  mmh::KinematicState s;
  s.position = Eigen::Vector3d(1, 2, 1.2);
  s.velocity = Eigen::Vector3d(2.4, 1.8, 0.0);  // 3 m/s
  s.acceleration = Eigen::Vector3d(-0.6, 0.8, 0.0);
  const std::vector<mmh::Trajectory> stops = mmh::makeSwervingStops(s, 2.0, 3.0);
  ASSERT_GE(stops.size(), 10u);
  const Eigen::Vector3d ahead = s.velocity.normalized();
  double previous_aside = 0.0;
  int left = 0, right = 0;
  for (const mmh::Trajectory& stop : stops) {
    EXPECT_LT((stop.position(0.0) - s.position).norm(), 1e-9);
    EXPECT_LT((stop.velocity(0.0) - s.velocity).norm(), 1e-9);
    EXPECT_LT((stop.acceleration(0.0) - s.acceleration).norm(), 1e-9);
    EXPECT_LT(stop.velocity(stop.duration()).norm(), 1e-9);
    EXPECT_LT(stop.acceleration(stop.duration()).norm(), 1e-9);
    EXPECT_LE(stop.maxAcceleration(), 2.0 * (1.0 + 1e-6));
    EXPECT_LE(stop.maxSpeed(), 3.0 * 1.0001);
    const Eigen::Vector3d end = stop.position(stop.duration()) - s.position;
    EXPECT_NEAR(end.z(), 0.0, 1e-9);  // in the horizontal plane
    EXPECT_GT(end.dot(ahead), 2.25);  // past the bang-bang stop (v^2 / 2 a_max)
    const double aside = ahead.x() * end.y() - ahead.y() * end.x();
    EXPECT_GE(std::abs(aside), previous_aside - 1e-9);
    EXPECT_LE(std::abs(aside), 1.0 + 1e-9);
    previous_aside = std::abs(aside);
    (aside > 0.0 ? left : right) += 1;
  }
  EXPECT_GT(left, 0);
  EXPECT_GT(right, 0);
  EXPECT_TRUE(mmh::makeSwervingStops(mmh::KinematicState{}, 2.0, 3.0).empty());  // at rest
}

// A newly mapped pillar stands beside the straight path where every stop that brakes along it (or
// straight) would come within its margin: the chosen stop swerves away from it, clear of its
// margin and of the check that found it, and within the limits. With the pillar farther, the
// stop brakes straight.
TEST(StoppingTrajectory, SwervesWhenNoStopThatBrakesIsClear) {
  const mmh::Trajectory path = steadyPath(3.0, 0.0);  // along x at 3 m/s from (0, 0, 1.2)
  const mmh::Trajectory straight = mmh::makeStoppingTrajectory(path, 0.5, 2.0, 3.0);
  const double stop_end_x = straight.position(straight.duration()).x();
  const mmh::VoxelGrid pillar = gridWithPillar(stop_end_x - 0.3, 0.2, 0.2);
  ASSERT_TRUE(mmh::firstCollisionTime(pillar, straight, 0.0, straight.duration()));

  const mmh::Trajectory chosen =
      mmh::chooseStoppingTrajectory(&pillar, path, 0.5, 2.0, 3.0, 0.25, kTouch);
  EXPECT_TRUE(mmh::isClearStop(pillar, chosen, 0.25));
  EXPECT_FALSE(mmh::firstCollisionTime(pillar, chosen, 0.0, chosen.duration()));
  EXPECT_GE(mmh::minOccupiedDistance(pillar, chosen, 1.0), 0.25);
  EXPECT_LT((chosen.state(0.0).velocity - path.velocity(0.5)).norm(), 1e-9);
  EXPECT_LT(chosen.velocity(chosen.duration()).norm(), 1e-9);
  EXPECT_LE(chosen.maxAcceleration(), 2.0 * (1.0 + 1e-6));
  EXPECT_LT(chosen.position(chosen.duration()).y(), -0.1);  // away from the pillar
  const mmh::Trajectory braking =
      mmh::chooseStoppingTrajectory(&pillar, path, 0.5, 2.0, 3.0, 0.25, kTouch, false);
  EXPECT_NEAR(braking.position(braking.duration()).y(), 0.0, 1e-9);  // not asked to swerve

  const mmh::VoxelGrid far = gridWithPillar(stop_end_x + 2.0, 0.0, 0.2);
  const mmh::Trajectory braked =
      mmh::chooseStoppingTrajectory(&far, path, 0.5, 2.0, 3.0, 0.25, kTouch);
  EXPECT_LT((braked.position(braked.duration()) - straight.position(straight.duration())).norm(),
            1e-9);
}

// A pillar stands on the straight path within braking distance and the clearance asked is wider
// than any stop can keep from it: no stop is clear. The stops that brake would run into the
// pillar, so the chosen one swerves and keeps the airframe off it, within the limits; asked not
// to swerve, it brakes into the pillar.
TEST(StoppingTrajectory, TakesASwerveThatKeepsTheAirframeOffWhenNoStopIsClear) {
  const mmh::Trajectory path = steadyPath(3.0, 0.0);  // along x at 3 m/s from (0, 0, 1.2)
  const mmh::Trajectory straight = mmh::makeStoppingTrajectory(path, 0.5, 2.0, 3.0);
  const double stop_end_x = straight.position(straight.duration()).x();
  const mmh::VoxelGrid pillar = gridWithPillar(stop_end_x - 0.3, 0.0, 0.2);
  const double unreachable_clearance_m = 1.5;
  for (const mmh::Trajectory& swerve : mmh::makeSwervingStops(path.state(0.5), 2.0, 3.0)) {
    ASSERT_FALSE(mmh::isClearStop(pillar, swerve, unreachable_clearance_m));
  }

  const mmh::Trajectory braking = mmh::chooseStoppingTrajectory(
      &pillar, path, 0.5, 2.0, 3.0, unreachable_clearance_m, kTouch, false);
  EXPECT_LT(mmh::minOccupiedDistance(pillar, braking, 1.0), kTouch);

  const mmh::Trajectory chosen =
      mmh::chooseStoppingTrajectory(&pillar, path, 0.5, 2.0, 3.0, unreachable_clearance_m, kTouch);
  EXPECT_FALSE(mmh::isClearStop(pillar, chosen, unreachable_clearance_m));
  EXPECT_GE(mmh::minOccupiedDistance(pillar, chosen, 1.0), kTouch);
  EXPECT_LT((chosen.state(0.0).velocity - path.velocity(0.5)).norm(), 1e-9);
  EXPECT_LT(chosen.velocity(chosen.duration()).norm(), 1e-9);
  EXPECT_LE(chosen.maxAcceleration(), 2.0 * (1.0 + 1e-6));
}

// A stop climbing at 45 degrees from 1.1 m to rest above 2.7 m: clear of every obstacle, but
// through the ceiling of a 2.7 m geofence, so not clear when that fence is given.
TEST(StoppingTrajectory, AStopThroughTheGeofenceIsNotClear) {
  mmh::KinematicState s;
  s.position = Eigen::Vector3d(1.0, 0.0, 1.1);
  s.velocity = Eigen::Vector3d(2.0, 0.0, 2.0);
  const mmh::Trajectory stop = mmh::makeStoppingTrajectory(s, 2.0, 3.0);
  ASSERT_GT(stop.position(stop.duration()).z(), 2.7);
  ASSERT_LT(stop.position(stop.duration()).z(), 2.9);  // inside the grid's 3 m
  const mmh::VoxelGrid clear = gridWithPillar(8.0, 0.0, 0.0);
  const mmh::Geofence fence{Eigen::Vector3d(-30, -30, 0.3), Eigen::Vector3d(30, 30, 2.7)};
  const mmh::Geofence high{Eigen::Vector3d(-30, -30, 0.3), Eigen::Vector3d(30, 30, 2.9)};
  EXPECT_TRUE(mmh::isClearStop(clear, stop, 0.25));
  EXPECT_TRUE(mmh::isClearStop(clear, stop, 0.25, &high));
  EXPECT_FALSE(mmh::isClearStop(clear, stop, 0.25, &fence));
}

// The caller's further condition (the arbiter's: no mapped obstacle's unseen side beside the
// stop) makes a stop unclear like an obstacle would: braking along the bend is refused, and the
// straight stop, which meets it, is taken.
TEST(StoppingTrajectory, ACallersFurtherConditionDecidesWhichStopIsClear) {
  const mmh::Trajectory path = bendingPath();
  const mmh::VoxelGrid clear = gridWithPillar(1.15, 0.6, 0.0);
  const mmh::Trajectory along = mmh::makeStoppingTrajectory(path, 0.0, 2.0, 3.0);
  const mmh::Trajectory straight = mmh::makeStoppingTrajectory(path.state(0.0), 2.0, 3.0);
  const Eigen::Vector3d along_end = along.position(along.duration());
  ASSERT_GT((straight.position(straight.duration()) - along_end).norm(), 0.05);
  auto endsElsewhere = [&](const mmh::Trajectory& t) {
    return (t.position(t.duration()) - along_end).norm() > 0.05;
  };
  EXPECT_TRUE(mmh::isClearStop(clear, along, 0.25));
  EXPECT_FALSE(mmh::isClearStop(clear, along, 0.25, nullptr, endsElsewhere));
  const mmh::Trajectory chosen = mmh::chooseStoppingTrajectory(
      &clear, path, 0.0, 2.0, 3.0, 0.25, kTouch, true, nullptr, endsElsewhere);
  EXPECT_TRUE(endsElsewhere(chosen));
  EXPECT_LT((chosen.velocity(0) - path.velocity(0)).norm(), 1e-9);
  EXPECT_LT(chosen.velocity(chosen.duration()).norm(), 1e-6);
}

namespace {

// A cruise along x: from rest at the origin to rest 20 m on, at up to about 3 m/s (4 pieces).
mmh::Trajectory cruise() {
  mmh::MincoJerk m;
  Eigen::Matrix3d head, tail;
  head << Eigen::Vector3d(0, 0, 1.2), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero();
  tail << Eigen::Vector3d(20, 3, 1.2), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero();
  m.setConditions(head, tail, 4);
  Eigen::Matrix3Xd inner(3, 3);
  inner << 3, 10, 17, 0, 2, 3, 1.2, 1.2, 1.2;
  m.setParameters(inner, Eigen::Vector4d(2.2, 2.6, 2.6, 2.2));
  return m.trajectory();
}

std::vector<Eigen::Vector3d> samplesOf(const mmh::Trajectory& t) {
  std::vector<Eigen::Vector3d> out;
  for (double s = 0.0; s <= t.duration(); s += 0.005) out.push_back(t.position(s));
  return out;
}

}  // namespace

// Answers come late, so the arbiter lowers the speed: the vehicle slows down on the path it
// flies, from exactly its state, within a_max, and flies the rest of it no faster than allowed.
TEST(SlowdownTrajectory, SlowsDownAlongThePathToTheAllowedSpeedAndEndsWhereItEnds) {
  const mmh::Trajectory path = cruise();
  ASSERT_GT(path.maxSpeed(), 2.8);
  const std::vector<Eigen::Vector3d> on_path = samplesOf(path);
  for (double allowed : {2.0, 1.2}) {
    const double t0 = 2.5;
    const mmh::Trajectory slow = mmh::makeSlowdownTrajectory(path, t0, allowed, 2.0);
    ASSERT_FALSE(slow.empty()) << allowed;
    const mmh::KinematicState s = path.state(t0);
    EXPECT_LT((slow.position(0) - s.position).norm(), 1e-9);
    EXPECT_LT((slow.velocity(0) - s.velocity).norm(), 1e-9);
    EXPECT_LT((slow.acceleration(0) - s.acceleration).norm(), 1e-9);
    EXPECT_LT((slow.position(slow.duration()) - path.position(path.duration())).norm(), 1e-9);
    EXPECT_LT(slow.velocity(slow.duration()).norm(), 1e-9);
    EXPECT_LE(slow.maxAcceleration(), 2.0 * (1.0 + 1e-6));
    // Slower than allowed (up to the fit's 2 %) once twice the stopping distance at the start
    // speed is flown (the transition brakes at 0.6 a_max on average), never faster than the path.
    const double settled_m = s.velocity.norm() * s.velocity.norm() / 2.0;
    double travelled = 0.0;
    for (double t = 0.0; t < slow.duration(); t += 0.01) {
      travelled += slow.velocity(t).norm() * 0.01;
      if (travelled > settled_m + 0.5) {
        EXPECT_LE(slow.velocity(t).norm(), allowed * 1.02) << t;
      }
      EXPECT_LE(slow.velocity(t).norm(), path.maxSpeed() * 1.0001);
      // The same curve: within 2 cm of the path everywhere.
      EXPECT_LT(distanceToSamples(on_path, slow.position(t)), 0.02) << t;
    }
    EXPECT_GT(slow.duration(), path.duration() - t0);
  }
}

TEST(SlowdownTrajectory, NothingToDoWhenThePathIsSlowEnough) {
  const mmh::Trajectory path = cruise();
  EXPECT_TRUE(mmh::makeSlowdownTrajectory(path, 1.0, path.maxSpeed() + 0.1, 2.0).empty());
  // Past the fastest part: what is left is slower than allowed.
  EXPECT_TRUE(mmh::makeSlowdownTrajectory(path, path.duration() - 0.5, 1.0, 2.0).empty());
  // A tiny share of the top speed would re-time the rest into ages: none (stop instead).
  EXPECT_TRUE(
      mmh::makeSlowdownTrajectory(path, 1.0, 0.5 * mmh::kMinSlowdownRatio * path.maxSpeed(), 2.0)
          .empty());
}

// Every failed round slows what the last one slowed: the curve is re-timed longer each time, but
// never past kLongestSlowdownS, so its fit (and every check of it) stays bounded.
TEST(SlowdownTrajectory, NoSlowdownLastsLongerThanTheLongestAllowed) {
  const mmh::Trajectory path = steadyPath(3.0, 0.0);  // 30 m in 10 s
  int made = 0;
  for (double speed = 3.0 * mmh::kMinSlowdownRatio; speed < 1.5; speed += 0.01) {
    const mmh::Trajectory slow = mmh::makeSlowdownTrajectory(path, 0.0, speed, 2.0);
    if (slow.empty()) continue;
    ++made;
    EXPECT_LE(slow.duration(), mmh::kLongestSlowdownS) << "at " << speed << " m/s";
  }
  EXPECT_GT(made, 50);
}
