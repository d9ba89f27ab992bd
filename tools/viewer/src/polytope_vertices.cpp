#include "mmh/viewer/polytope_vertices.hpp"

#include <Eigen/LU>
#include <cmath>

namespace mmh::viewer {

std::vector<Eigen::Vector3d> polytopeVertices(const std::vector<Eigen::Vector4d>& faces,
                                              double tolerance_m, double merge_m) {
  std::vector<Eigen::Vector3d> out;
  const size_t n = faces.size();
  const auto inside = [&](const Eigen::Vector3d& x) {
    for (const Eigen::Vector4d& f : faces) {
      if (f.head<3>().dot(x) - f[3] > tolerance_m) return false;
    }
    return true;
  };
  const auto known = [&](const Eigen::Vector3d& x) {
    for (const Eigen::Vector3d& v : out) {
      if ((v - x).squaredNorm() < merge_m * merge_m) return true;
    }
    return false;
  };
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i + 1; j < n; ++j) {
      for (size_t k = j + 1; k < n; ++k) {
        Eigen::Matrix3d a;
        a.row(0) = faces[i].head<3>().transpose();
        a.row(1) = faces[j].head<3>().transpose();
        a.row(2) = faces[k].head<3>().transpose();
        if (std::abs(a.determinant()) < 1e-9) continue;  // parallel faces meet in no point
        const Eigen::Vector3d x =
            a.partialPivLu().solve(Eigen::Vector3d(faces[i][3], faces[j][3], faces[k][3]));
        if (x.allFinite() && inside(x) && !known(x)) out.push_back(x);
      }
    }
  }
  if (out.size() < 4) out.clear();  // not a solid
  return out;
}

}  // namespace mmh::viewer
