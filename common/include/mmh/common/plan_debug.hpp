// What a planning mode computed for one answer, as its library reports it (no LCM): the paths it
// searched, SOM's corridor and EAM's B-spline with its {p, v} anchor pairs. The nodes publish it
// as plan_debug_t (msg_convert.hpp) when their publish_debug key is set; the ground station
// draws it (docs/viewer.md#the-debug-layer).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace mmh {

struct PlanDebug {
  struct AnchorPair {
    int control_point = 0;  // index into control_points
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    Eigen::Vector3d v = Eigen::Vector3d::UnitX();
  };
  // SOM: the shortened A* path; EAM: the A* guides.
  std::vector<std::vector<Eigen::Vector3d>> paths;
  // SOM: the corridor's polytopes, rows (a^T, b) of a . x <= b.
  std::vector<Eigen::Matrix<double, Eigen::Dynamic, 4>> polytopes;
  // EAM: the B-spline's control points and anchor pairs.
  std::vector<Eigen::Vector3d> control_points;
  std::vector<AnchorPair> pairs;
};

}  // namespace mmh
