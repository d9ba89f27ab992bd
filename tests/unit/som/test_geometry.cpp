// Geometry of the corridor: polytopes, the inscribed ellipsoid, the separating plane of the
// hyperplane round, FIRI inflation and the extraction of obstacle points from the grid.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "mmh/som/ellipsoid.hpp"
#include "mmh/som/obstacle_points.hpp"
#include "mmh/som/polytope.hpp"
#include "mmh/som/polytope_inflation.hpp"
#include "som_test_worlds.hpp"

using Eigen::Vector3d;
using mmh::som::Ellipsoid;
using mmh::som::Polytope;

namespace {

Polytope box(const Vector3d& lo, const Vector3d& hi) {
  Polytope p;
  p.addBox(lo, hi);
  return p;
}

// The ellipsoid lies inside the polytope: its support in every face normal is below b.
bool ellipsoidInside(const Ellipsoid& e, const Polytope& p, double tol = 1e-9) {
  for (int i = 0; i < p.numHalfspaces(); ++i) {
    const Vector3d a = p.halfspaces().row(i).head<3>().transpose();
    if (e.support(a) > p.halfspaces()(i, 3) + tol) return false;
  }
  return true;
}

}  // namespace

TEST(Polytope, ContainsAndLineInterval) {
  const Polytope p = box(Vector3d(0, 0, 0), Vector3d(2, 1, 1));
  EXPECT_TRUE(p.contains(Vector3d(1, 0.5, 0.5)));
  EXPECT_TRUE(p.contains(Vector3d(1, 0.5, 0.5), 0.49));
  EXPECT_FALSE(p.contains(Vector3d(1, 0.5, 0.5), 0.51));
  EXPECT_FALSE(p.contains(Vector3d(2.1, 0.5, 0.5)));
  EXPECT_NEAR(p.maxViolation(Vector3d(2.5, 0.5, 0.5)), 0.5, 1e-12);
  double lo, hi;
  ASSERT_TRUE(p.lineInterval(Vector3d(0, 0.5, 0.5), 0, &lo, &hi));
  EXPECT_NEAR(lo, 0.0, 1e-12);
  EXPECT_NEAR(hi, 2.0, 1e-12);
  EXPECT_FALSE(p.lineInterval(Vector3d(0, 1.5, 0.5), 0, &lo, &hi));
  Polytope q;
  EXPECT_FALSE(q.addHalfspace(Vector3d::Zero(), 1.0));
  EXPECT_TRUE(q.addHalfspace(Vector3d(0, 0, 2), 4.0));  // normalised to z <= 2
  EXPECT_NEAR(q.halfspaces()(0, 3), 2.0, 1e-12);
}

TEST(InscribedEllipsoid, BoxGivesTheAxisAlignedEllipsoid) {
  const Polytope p = box(Vector3d(0, 0, 0), Vector3d(4, 2, 1));
  Ellipsoid start;
  start.center = Vector3d(0.5, 0.5, 0.5);
  start.shape = 0.1 * Eigen::Matrix3d::Identity();
  // The maximum-volume ellipsoid of a box has the half edges as semi-axes. A small final barrier
  // weight gets close to it.
  const double ideal = 4.0 / 3.0 * M_PI * 2.0 * 1.0 * 0.5;
  mmh::som::InscribedEllipsoidOptions accurate;
  accurate.barrier_start = 1e-1;
  accurate.barrier_final = 1e-4;
  accurate.max_newton_steps = 30;
  Ellipsoid e, quick;
  ASSERT_TRUE(mmh::som::inscribedEllipsoid(p, start, &e, accurate));
  EXPECT_TRUE(ellipsoidInside(e, p));
  EXPECT_GT(e.volume(), 0.99 * ideal);
  EXPECT_LE(e.volume(), ideal * (1 + 1e-9));
  EXPECT_LT((e.center - Vector3d(2, 1, 0.5)).norm(), 0.01);
  // The corridor's default is a few damped Newton steps: inside, and far grown from the start.
  ASSERT_TRUE(mmh::som::inscribedEllipsoid(p, start, &quick));
  EXPECT_TRUE(ellipsoidInside(quick, p));
  EXPECT_GT(quick.volume(), 0.5 * ideal);
  EXPECT_GT(quick.volume(), 100.0 * start.volume());
}

TEST(InscribedEllipsoid, SimplexGivesTheInsphere) {
  // Regular tetrahedron: its maximum-volume inscribed ellipsoid is the insphere.
  const Vector3d v[4] = {Vector3d(1, 1, 1), Vector3d(1, -1, -1), Vector3d(-1, 1, -1),
                         Vector3d(-1, -1, 1)};
  Polytope p;
  for (int i = 0; i < 4; ++i) {
    const Vector3d c = (v[(i + 1) % 4] + v[(i + 2) % 4] + v[(i + 3) % 4]) / 3.0;
    const Vector3d n = c.normalized();  // outward (the centroid is the origin)
    p.addHalfspace(n, n.dot(c));
  }
  Ellipsoid start;
  start.shape = 0.05 * Eigen::Matrix3d::Identity();
  start.center = Vector3d(0.2, -0.1, 0.05);
  mmh::som::InscribedEllipsoidOptions accurate;
  accurate.barrier_start = 1e-1;
  accurate.barrier_final = 1e-4;
  accurate.max_newton_steps = 30;
  Ellipsoid e;
  ASSERT_TRUE(mmh::som::inscribedEllipsoid(p, start, &e, accurate));
  EXPECT_TRUE(ellipsoidInside(e, p));
  const double r = 1.0 / std::sqrt(3.0);  // inradius of this tetrahedron
  EXPECT_GT(e.volume(), 0.99 * 4.0 / 3.0 * M_PI * r * r * r);
  EXPECT_LT(e.center.norm(), 0.01);
}

TEST(InscribedEllipsoid, RefusesACentreOutside) {
  const Polytope p = box(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  Ellipsoid start;
  start.center = Vector3d(2, 0.5, 0.5);
  Ellipsoid e;
  EXPECT_FALSE(mmh::som::inscribedEllipsoid(p, start, &e));
}

TEST(SeparatingPlane, PassesThroughThePointAndKeepsTheSeed) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  int solved = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const Vector3d x(u(rng), u(rng), u(rng)), a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
    Vector3d y;
    if (!mmh::som::separatingPlane(x, a, b, &y)) continue;
    ++solved;
    EXPECT_NEAR(y.dot(x), 1.0, 1e-9);
    EXPECT_LE(y.dot(a), 1.0 + 1e-7);
    EXPECT_LE(y.dot(b), 1.0 + 1e-7);
    // No feasible plane is farther from the origin: compare with random feasible normals.
    for (int k = 0; k < 20; ++k) {
      Vector3d z(u(rng), u(rng), u(rng));
      if (std::abs(z.dot(x)) < 1e-6) continue;
      z /= z.dot(x);  // z . x = 1
      if (z.dot(a) <= 1.0 && z.dot(b) <= 1.0) {
        EXPECT_GE(z.norm(), y.norm() - 1e-9);
      }
    }
  }
  EXPECT_GT(solved, 100);
  // A point on the seed cannot be separated.
  Vector3d y;
  EXPECT_FALSE(mmh::som::separatingPlane(Vector3d(0.5, 0, 0), Vector3d(0, 0, 0) - Vector3d(1, 0, 0),
                                         Vector3d(1, 0, 0), &y));
}

TEST(SeparatingPlane, KeepsAThreePointSeedAndIsOptimal) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  int solved = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const Vector3d x(u(rng), u(rng), u(rng));
    const Vector3d seed[3] = {Vector3d(u(rng), u(rng), u(rng)), Vector3d(u(rng), u(rng), u(rng)),
                              Vector3d(u(rng), u(rng), u(rng))};
    Vector3d y;
    if (!mmh::som::separatingPlane(x, seed, 3, &y)) continue;
    ++solved;
    EXPECT_NEAR(y.dot(x), 1.0, 1e-9);
    for (const Vector3d& v : seed) EXPECT_LE(y.dot(v), 1.0 + 1e-7);
    for (int k = 0; k < 20; ++k) {
      Vector3d z(u(rng), u(rng), u(rng));
      if (std::abs(z.dot(x)) < 1e-6) continue;
      z /= z.dot(x);
      if (z.dot(seed[0]) <= 1.0 && z.dot(seed[1]) <= 1.0 && z.dot(seed[2]) <= 1.0) {
        EXPECT_GE(z.norm(), y.norm() - 1e-9);
      }
    }
  }
  EXPECT_GT(solved, 50);
  // A point inside the seed triangle cannot be separated with room to spare (only the plane of
  // the triangle itself touches it).
  const Vector3d tri[3] = {Vector3d(1, 0, 0), Vector3d(0, 1, 0), Vector3d(-1, -1, 0.5)};
  Vector3d y;
  EXPECT_FALSE(mmh::som::separatingPlane((tri[0] + tri[1] + tri[2]) / 3.0, tri, 3, &y, 1e-3));
}

TEST(PolytopeInflation, ExcludesEveryPointAndKeepsTheSeed) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Vector3d a(-1.0, 0.0, 0.0), b(1.0, 0.3, 0.1);
    std::vector<Vector3d> points;
    while (points.size() < 300) {
      const Vector3d p(u(rng), u(rng), u(rng));
      // Keep points off a tube around the seed.
      const Vector3d ab = b - a;
      const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      if ((a + t * ab - p).norm() > 0.3) points.push_back(p);
    }
    mmh::som::PolytopeInflator inflator;
    mmh::som::InflationOptions options;
    options.iterations = 3;
    Polytope poly;
    Ellipsoid metric;
    ASSERT_TRUE(inflator.inflate(points, Vector3d::Constant(-3), Vector3d::Constant(3), {a, b},
                                 options, &poly, &metric));
    for (const Vector3d& p : points) EXPECT_GT(poly.maxViolation(p), 0.0);
    EXPECT_LT(poly.maxViolation(a), 0.0);
    EXPECT_LT(poly.maxViolation(b), 0.0);
    EXPECT_GT(poly.maxViolation(Vector3d(3.01, 0, 0)), 0.0);  // bounded by the box
  }
}

TEST(ObstaclePoints, SurfaceAndInsidePointsMatchABruteForceScan) {
  const som_test::World w = som_test::pillars();
  const mmh::VoxelGrid& g = *w.grid;
  const Vector3d lo(2.0, -1.5, 0.3), hi(6.0, 1.5, 2.0);
  std::vector<Vector3d> surface;
  mmh::som::blockedSurfacePoints(g, lo, hi, {}, &surface);
  // Brute force: blocked cells with a non-blocked 6-neighbour, centre inside the box.
  size_t expected = 0;
  for (int64_t i = 0; i < g.numCells(); ++i) {
    const Eigen::Vector3i c = g.localFromLinear(i);
    const Vector3d p = g.centerOfLocal(c);
    if (!g.isBlockedLinear(i) || !som_test::inBox(p, lo, hi)) continue;
    bool surf = false;
    for (int d = 0; d < 3; ++d)
      for (int s : {-1, 1}) surf = surf || !g.isBlocked(c + s * Eigen::Vector3i::Unit(d));
    expected += surf;
  }
  EXPECT_EQ(surface.size(), expected);
  EXPECT_GT(expected, 100u);
  for (const Vector3d& p : surface) EXPECT_TRUE(g.isBlockedPoint(p));

  // Every blocked centre inside a polytope, against a scan of the whole window.
  Polytope poly = box(lo, hi);
  poly.addHalfspace(Vector3d(1, 1, 0), 5.0);
  std::vector<Vector3d> inside;
  mmh::som::blockedPointsInside(g, lo, hi, poly, {}, &inside);
  size_t count = 0;
  for (int64_t i = 0; i < g.numCells(); ++i) {
    const Vector3d p = g.centerOfLocal(g.localFromLinear(i));
    if (g.isBlockedLinear(i) && som_test::inBox(p, lo, hi) && poly.maxViolation(p) < 0.0) ++count;
  }
  EXPECT_EQ(inside.size(), count);
  EXPECT_GT(count, 10u);
}

TEST(ObstaclePoints, EscapeZoneFreesOnlyTheMarginAroundTheStart) {
  const som_test::World w = som_test::pillars();
  const mmh::VoxelGrid& g = *w.grid;
  // A start inside the inflated margin of the pillar at (3, 0.2) r 0.3: 0.45 m from its axis.
  mmh::som::EscapeZone escape{Vector3d(3.0, 0.65, 1.2), 0.5};
  ASSERT_TRUE(g.isBlockedPoint(escape.center));
  std::vector<Vector3d> with, without;
  const Vector3d lo(2.0, -1.0, 1.0), hi(4.0, 1.5, 1.4);
  mmh::som::blockedSurfacePoints(g, lo, hi, escape, &with);
  mmh::som::blockedSurfacePoints(g, lo, hi, {}, &without);
  EXPECT_NE(with.size(), without.size());
  for (const Vector3d& p : with) {
    // Escape-zone cells that are only inflated are not obstacles; occupied ones still are.
    if ((p - escape.center).norm() <= escape.radius) {
      EXPECT_TRUE(g.isOccupiedPoint(p));
    }
  }
}

// The pillars (inflated 0.3 m) seen through the arbiter's 0.25 m check margin, and a box of
// them: the surface points without check-margin points, and with them (faces only, or whole-cell
// fences).
struct CheckMarginPoints {
  explicit CheckMarginPoints(bool whole_cells) : w(som_test::pillars()), check(*w.grid) {
    check.setInflationRadius(0.25);
    mmh::som::BlockedMask mask;
    built = mask.build(*w.grid, lo, hi, {});
    mask.surfacePoints(&plain);
    built = built && mask.build(*w.grid, lo, hi, {}, 0.25, clearance, whole_cells);
    mask.surfacePoints(&with_margin);
  }
  som_test::World w;
  mmh::VoxelGrid check;
  const Vector3d lo = Vector3d(2.0, -1.5, 0.3), hi = Vector3d(6.0, 1.5, 2.0);
  const double clearance = 0.021;  // SOM's: the verification's corridor tolerance + 1 mm
  bool built = false;
  std::vector<Vector3d> plain, with_margin;
};

TEST(ObstaclePoints, CellsTheArbitersMarginBlocksAreFencedJustBeyondTheCorridorTolerance) {
  const CheckMarginPoints m(false);
  ASSERT_TRUE(m.built);
  const mmh::VoxelGrid& g = *m.w.grid;
  // Brute force: one point per face between a surface cell that the 0.25 m margin blocks and an
  // unblocked 6-neighbour, `clearance` off that face inside the neighbour, so that a trajectory
  // that leaves its polytope by less than that does not touch the blocked cell.
  size_t expected = 0;
  for (int64_t i = 0; i < g.numCells(); ++i) {
    const Eigen::Vector3i c = g.localFromLinear(i);
    if (!g.isBlockedLinear(i) || !m.check.isBlocked(c) ||
        !som_test::inBox(g.centerOfLocal(c), m.lo, m.hi))
      continue;
    for (int d = 0; d < 3; ++d)
      for (int s : {-1, 1}) expected += !g.isBlocked(c + s * Eigen::Vector3i::Unit(d));
  }
  ASSERT_GT(expected, 50u);
  ASSERT_EQ(m.with_margin.size(), m.plain.size() + expected);
  for (size_t k = m.plain.size(); k < m.with_margin.size(); ++k) {
    const Vector3d& q = m.with_margin[k];
    EXPECT_FALSE(g.isBlockedPoint(q));
    // `clearance` from a cell face, and that face is a blocked cell's.
    const Vector3d r = q / g.resolution();
    const Vector3d off = r - r.array().round().matrix();
    int axis = 0;
    off.cwiseAbs().minCoeff(&axis);
    EXPECT_NEAR(std::abs(off[axis]) * g.resolution(), m.clearance, 1e-5);
    Vector3d across = q;
    across[axis] -= (off[axis] > 0 ? 1 : -1) * (m.clearance + 1e-4);
    EXPECT_TRUE(m.check.isBlockedPoint(across));
  }
}

TEST(ObstaclePoints, WholeCellFencesSurroundEveryCellOfTheArbitersMarginBesideOneOutsideIt) {
  const CheckMarginPoints m(true);
  ASSERT_TRUE(m.built);
  const mmh::VoxelGrid& g = *m.w.grid;
  // Brute force: per cell within the 0.25 m margin and neighbour (of 26) outside it, the 3 x 3
  // points of their common face, or one point at their common edge or corner; each `clearance`
  // beyond the cell along every axis the neighbour lies on, and no nearer to the cell.
  size_t expected = 0;
  for (int64_t i = 0; i < g.numCells(); ++i) {
    const Eigen::Vector3i c = g.localFromLinear(i);
    if (!m.check.isBlocked(c) || !som_test::inBox(g.centerOfLocal(c), m.lo, m.hi)) continue;
    for (int z = -1; z <= 1; ++z)
      for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) {
          const Eigen::Vector3i d(x, y, z);
          if (d.isZero() || m.check.isBlocked(c + d)) continue;
          expected += d.cwiseAbs().sum() == 1 ? 9 : 1;
        }
  }
  ASSERT_GT(expected, 500u);
  ASSERT_EQ(m.with_margin.size(), m.plain.size() + expected);
  for (size_t k = m.plain.size(); k < m.with_margin.size(); ++k) {
    const Vector3d r = m.with_margin[k] / g.resolution();
    const Vector3d off = (r - r.array().round().matrix()).cwiseAbs() * g.resolution();
    // Along each axis on a cell boundary, on a cell's middle or `clearance` beyond a boundary;
    // beyond one along at least one axis.
    int beyond = 0;
    for (int a = 0; a < 3; ++a) {
      const bool on = off[a] < 1e-5 || std::abs(off[a] - 0.5 * g.resolution()) < 1e-5;
      const bool past = std::abs(off[a] - m.clearance) < 1e-5;
      EXPECT_TRUE(on || past) << off.transpose();
      beyond += past;
    }
    EXPECT_GE(beyond, 1);
  }
}
