// Writes a minimal ASCII PCD file (x y z) for tests, without depending on PCL.
#pragma once

#include <Eigen/Core>
#include <fstream>
#include <string>
#include <vector>

namespace mmh::test {

inline void writePcd(const std::string& path, const std::vector<Eigen::Vector3f>& points) {
  std::ofstream out(path);
  out << "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\n"
         "TYPE F F F\nCOUNT 1 1 1\nWIDTH "
      << points.size() << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << points.size()
      << "\nDATA ascii\n";
  for (const auto& p : points) out << p.x() << " " << p.y() << " " << p.z() << "\n";
}

// Surface points of a wall x = x0, |y| <= half_width, 0 <= z <= height, spaced `step`.
inline std::vector<Eigen::Vector3f> wallPoints(double x0, double half_width, double height,
                                               double step) {
  std::vector<Eigen::Vector3f> out;
  for (double y = -half_width; y <= half_width + 1e-9; y += step)
    for (double z = 0.0; z <= height + 1e-9; z += step)
      out.emplace_back(static_cast<float>(x0), static_cast<float>(y), static_cast<float>(z));
  return out;
}

}  // namespace mmh::test
