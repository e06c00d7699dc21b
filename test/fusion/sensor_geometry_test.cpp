#include <gtest/gtest.h>

#include <numbers>

#include "hal/pan_tilt_geometry.hpp"
#include "hal/stripe_geometry.hpp"

namespace rangefit::hal {
namespace sensor_geometry_test {

TEST(StripeRanger, FanRaysSpanTheFanAngleSymmetricallyInTheLaserPlane) {
  const StripeRanger r;
  const Eigen::Vector3d first = r.ray_direction(0, r.points_per_profile);
  const Eigen::Vector3d last = r.ray_direction(r.points_per_profile - 1, r.points_per_profile);
  EXPECT_DOUBLE_EQ(first.y(), 0.0);
  EXPECT_NEAR(first.x(), -last.x(), 1e-12);
  EXPECT_NEAR(std::acos(first.dot(last)), r.fan_angle_rad, 1e-12);
}

TEST(StripeCellGeometry, DefaultRangerLooksDownOntoTheTable) {
  const StripeCellGeometry g;
  // The fan's centre ray at 600 mm depth hits the table surface (z = 0) at the laser plane.
  const Eigen::Vector3d hit = g.T_world_ranger(0.0) * StripeRanger::ranger_point(0.0, 600.0);
  EXPECT_NEAR(hit.x(), 0.0, 1e-9);
  EXPECT_NEAR(hit.y(), 200.0, 1e-9);
  EXPECT_NEAR(hit.z(), 0.0, 1e-9);
}

TEST(StripeCellGeometry, MovingTheAxisMovesTheScannedTableLineBackwards) {
  const StripeCellGeometry g;
  const Eigen::Vector3d p = StripeRanger::ranger_point(10.0, 500.0);
  const Eigen::Vector3d a = g.T_world_ranger(0.0) * p;
  const Eigen::Vector3d b = g.T_world_ranger(150.0) * p;
  EXPECT_NEAR((a - b - Eigen::Vector3d(0, 150, 0)).norm(), 0.0, 1e-9);
}

TEST(PanTiltGeometry, MatchesEquation5_7) {
  PanTiltGeometry g;
  g.t_s_mm = {1.0, 2.0, 3.0};
  g.t_w_mm = {10.0, 20.0, 30.0};
  const double a = 0.3, b = -0.2;
  Eigen::Matrix3d rx, ry;
  rx << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  ry << std::cos(b), 0, std::sin(b), 0, 1, 0, -std::sin(b), 0, std::cos(b);
  const Eigen::Vector3d xs(5.0, 0.0, 700.0);
  const Eigen::Vector3d expected = rx * ry * (xs + g.t_s_mm) + g.t_w_mm;
  EXPECT_NEAR((g.T_world_ranger(a, b) * xs - expected).norm(), 0.0, 1e-9);
}

}  // namespace sensor_geometry_test
}  // namespace rangefit::hal
