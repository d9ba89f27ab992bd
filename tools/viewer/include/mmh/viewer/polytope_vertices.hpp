// The corners of a corridor polytope given by its faces, for drawing (PLAN_DEBUG carries the
// faces, a . x <= b, as the planner has them; a browser needs points).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace mmh::viewer {

// Vertices of the bounded polytope {x : a_i . x <= b_i} (each face as (a_i, b_i), a_i a unit
// normal): every point where three faces meet that no face excludes by more than tolerance_m,
// each once (points closer than merge_m are one). Empty if the polytope is empty or flat.
std::vector<Eigen::Vector3d> polytopeVertices(const std::vector<Eigen::Vector4d>& faces,
                                              double tolerance_m = 1e-4, double merge_m = 1e-3);

}  // namespace mmh::viewer
