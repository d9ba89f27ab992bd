// A thin vertical elliptic ring (a tube around an ellipse standing in a vertical plane), the
// second obstacle of the EGO-Planner / Fast-Planner random forest: exact distance to its surface
// and ray intersection by sphere tracing on that distance.
#pragma once

#include <Eigen/Core>

namespace mmh::sim {

struct EllipticRing {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  // The ring's plane is vertical; its normal is (cos yaw, sin yaw, 0), so yaw 0 faces the x axis
  // (the flight direction of the benchmark's missions).
  double yaw = 0.0;
  double semi_horizontal_m = 0.6;  // semi-axis along the horizontal in-plane direction
  double semi_vertical_m = 1.0;    // semi-axis along z
  double tube_radius_m = 0.05;
  // Radius of a sphere around the centre that contains the whole ring.
  double boundingRadius() const;
};

// Distance in the plane from (u, v) to the curve u^2/a^2 + v^2/b^2 = 1 (a, b > 0); exact up to
// rounding (Eberly's bisection on the foot-point equation).
double distanceToEllipseCurve(double a, double b, double u, double v);

// Distance from p to the ring's tube surface, negative inside the tube.
double distanceToRing(const EllipticRing& ring, const Eigen::Vector3d& p);

// Distance along the unit ray origin + t dir (0 <= t <= max_range) to the tube surface, within
// 1e-4 m; negative if it misses; 0 if the origin is inside.
double rayRing(const EllipticRing& ring, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
               double max_range);

}  // namespace mmh::sim
