// Convex polytope in H-representation {x : a_i . x <= b_i} with unit normals a_i, the building
// block of the safe flight corridor.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace mmh::som {

class Polytope {
 public:
  // Row i is (a_i^T, b_i).
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, 4>;

  Polytope() = default;
  explicit Polytope(Matrix h) : h_(std::move(h)) {}

  const Matrix& halfspaces() const { return h_; }
  int numHalfspaces() const { return static_cast<int>(h_.rows()); }
  // Adds a . x <= b (a need not be normalised; it is normalised here). Returns false for a = 0.
  bool addHalfspace(const Eigen::Vector3d& a, double b);
  // The six faces of an axis-aligned box.
  void addBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

  // max_i (a_i . p - b_i): <= 0 inside, the distance outside the worst face otherwise.
  double maxViolation(const Eigen::Vector3d& p) const;
  bool contains(const Eigen::Vector3d& p, double margin = 0.0) const {
    return maxViolation(p) <= -margin;
  }
  // Interval [lo, hi] of t with p + t e_axis inside; false if empty.
  bool lineInterval(const Eigen::Vector3d& p, int axis, double* lo, double* hi) const;

 private:
  Matrix h_;
};

}  // namespace mmh::som
