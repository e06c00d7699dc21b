// Whether a part could rest on the table as posed (object_stability.hpp): a cone stands on its
// base or lies on its side; on its apex or with its axis level it topples.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "detect/object/object_stability.hpp"
#include "sim/scene_objects.hpp"
#include "test/detect/varied_target.hpp"

namespace rangefit {
namespace {

constexpr double kLimit = 0.15;  // ObjectDetectOptions::max_settle_rad
const Eigen::Vector3d kUp = Eigen::Vector3d::UnitZ();

// The part's z-axis turned from up by `tilt` about the x-axis.
Eigen::Matrix3d tilted(double tilt) {
  return Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()).toRotationMatrix();
}

TEST(PartCentroid, AFullConesIsAQuarterOfItsHeightAboveItsBase) {
  // Base radius 40 at z = -40, apex at z = +40.
  const Superquadric cone = sim::cone_model();
  EXPECT_NEAR(part_centroid(cone).z(), -40.0 + 80.0 / 4.0, 0.3);
  EXPECT_NEAR(part_centroid({20, 20, 40, 0.1, 1.0, 0.0, 0.0}).z(), 0.0, 1e-9);
}

TEST(SettleAngle, AConeRestsOnItsBaseAndOnItsSide) {
  const Superquadric cone = sim::cone_model();
  EXPECT_LT(settle_angle_rad(cone, tilted(0.0), kUp, 2 * kLimit), 1e-9);
  EXPECT_LE(settle_angle_rad(cone, tilted(0.05), kUp, 2 * kLimit), kLimit);  // a fit's tilt
  // On its side: its apex on the table and its axis rising from there by the half-angle
  // (atan(40 / 80)) towards the base, a generator line on the table.
  const double side = std::numbers::pi / 2.0 + std::atan(40.0 / 80.0);
  EXPECT_LE(settle_angle_rad(cone, tilted(side), kUp, 2 * kLimit), kLimit);
}

TEST(SettleAngle, AConeOnItsApexOrWithItsAxisLevelTopples) {
  const Superquadric cone = sim::cone_model();
  EXPECT_GT(settle_angle_rad(cone, tilted(std::numbers::pi), kUp, 2 * kLimit), kLimit);
  EXPECT_GT(settle_angle_rad(cone, tilted(std::numbers::pi / 2.0), kUp, 2 * kLimit), kLimit);
}

TEST(SettleAngle, ABallAndALyingCanDoNotRoll) {
  EXPECT_LT(settle_angle_rad(sim::sphere_model(), tilted(0.7), kUp, 2 * kLimit), 1e-9);
  const Superquadric can{30, 30, 50, 0.1, 1.0, 0.0, 0.0};
  EXPECT_LE(settle_angle_rad(can, tilted(std::numbers::pi / 2.0), kUp, 2 * kLimit), kLimit);
}

// Pan-tilt varied scenes (tuning seeds) where a cone fitted apex down onto a clutter box's top
// face (its base on the face) explained the scan as well as the true cone, and was taken:
// seeds 34 and 191. It topples; the true cone is found.
TEST(ObjectStability, AConeFittedApexDownOntoABoxIsNotTaken) {
  for (std::uint64_t seed : {34u, 191u}) {
    test::expect_varied_target_found(sim::VariedTarget::kCone, seed, true);
  }
}

}  // namespace
}  // namespace rangefit
