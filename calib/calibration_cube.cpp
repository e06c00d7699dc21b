#include "calib/calibration_cube.hpp"

#include <Eigen/LU>
#include <limits>

namespace rangefit::calib {

std::array<CubePlane, 6> visible_planes(const CalibrationCube& cube,
                                        const Eigen::Isometry3d& T_F_cube,
                                        const Eigen::Vector3d& towards_sensor_F) {
  const Eigen::Vector3d v = T_F_cube.linear().transpose() * towards_sensor_F;
  const double h = 0.5 * cube.edge_mm;
  std::array<CubePlane, 6> out;
  for (int a = 0; a < 3; ++a) {
    const double sign = v[a] >= 0.0 ? 1.0 : -1.0;
    const Eigen::Vector3d n = sign * T_F_cube.linear().col(a);
    const double centre = n.dot(T_F_cube.translation());
    // Outer face at +h along n; the far bars' inner face at -(h - bar) along n.
    out[static_cast<std::size_t>(2 * a)] = {n, centre + h, a, true};
    out[static_cast<std::size_t>(2 * a + 1)] = {n, centre - (h - cube.bar_mm), a, false};
  }
  return out;
}

Eigen::Vector3d intersect_planes(const Eigen::Vector3d& n0, double d0, const Eigen::Vector3d& n1,
                                 double d1, const Eigen::Vector3d& n2, double d2) {
  Eigen::Matrix3d A;
  A.row(0) = n0.transpose();
  A.row(1) = n1.transpose();
  A.row(2) = n2.transpose();
  if (std::abs(A.determinant()) < 1e-9) {
    return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  }
  return A.partialPivLu().solve(Eigen::Vector3d(d0, d1, d2));
}

Eigen::Vector3d corner_point(const std::array<CubePlane, 6>& planes, int c) {
  const auto& p0 = planes[static_cast<std::size_t>(0 + ((c >> 0) & 1))];
  const auto& p1 = planes[static_cast<std::size_t>(2 + ((c >> 1) & 1))];
  const auto& p2 = planes[static_cast<std::size_t>(4 + ((c >> 2) & 1))];
  return intersect_planes(p0.normal, p0.offset_mm, p1.normal, p1.offset_mm, p2.normal,
                          p2.offset_mm);
}

}  // namespace rangefit::calib
