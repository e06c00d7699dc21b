#pragma once
// The hollow calibration cube of twelve bars (sim/calibration_scans.hpp) as a scene file for the
// simulated cell, held by its fixture at T in the scene frame, on a table or alone.

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>

#include "detect/common/angles.hpp"

namespace rangefit::test {

inline void write_cube_scene(const std::filesystem::path& path, double edge, double bar,
                             const Eigen::Isometry3d& T, bool table) {
  std::ofstream out(path);
  out.precision(12);
  if (table) out << "[[object]]\nname = \"table\"\ntype = \"plane\"\nsize = [2000, 2000]\n";
  const double c = 0.5 * edge - 0.5 * bar;
  const Eigen::Vector3d rpy = T.linear().eulerAngles(2, 1, 0).reverse() / kDeg;
  int n = 0;
  for (int a = 0; a < 3; ++a) {
    for (int s1 = -1; s1 <= 1; s1 += 2) {
      for (int s2 = -1; s2 <= 1; s2 += 2) {
        Eigen::Vector3d size = Eigen::Vector3d::Constant(bar), centre = Eigen::Vector3d::Zero();
        size[a] = edge;
        centre[(a + 1) % 3] = s1 * c;
        centre[(a + 2) % 3] = s2 * c;
        const Eigen::Vector3d p = T * centre;
        out << "[[object]]\nname = \"bar" << n++ << "\"\ntype = \"box\"\nsize = [" << size.x()
            << ", " << size.y() << ", " << size.z() << "]\nposition = [" << p.x() << ", " << p.y()
            << ", " << p.z() << "]\nrpy_deg = [" << rpy.x() << ", " << rpy.y() << ", " << rpy.z()
            << "]\n";
      }
    }
  }
}

}  // namespace rangefit::test
