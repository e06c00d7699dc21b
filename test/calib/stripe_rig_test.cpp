// Two cameras triangulating one laser plane from its two sides (thesis 3.2.1, fig. 3.6b),
// calibrated together from their sweeps of the hollow cube.
#include <gtest/gtest.h>

#include <numbers>

#include "calib/stripe_calibration.hpp"
#include "calib_fixtures.hpp"

namespace rangefit::test {
namespace stripe_rig_test {

double position_error(const calib::StripeCalibrationResult& r, const hal::StripeCellGeometry& t) {
  return (r.geometry.ranger_position_cell_mm - t.ranger_position_cell_mm).norm();
}
double rotation_error(const calib::StripeCalibrationResult& r, const hal::StripeCellGeometry& t) {
  return angle_between(r.geometry.T_cell_ranger().linear(), t.T_cell_ranger().linear());
}

class StripeRigSeeds : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(StripeRigSeeds, BothCamerasAndTheAxisAreRecoveredFromAStartFarOff) {
  const Rig rig = two_sided_rig(GetParam(), {});
  const calib::StripeRigResult r = calibrate_rig(rig.a, rig.b);
  ASSERT_TRUE(r.ok) << r.reason;
  ASSERT_EQ(r.cameras.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const hal::StripeCellGeometry& truth = k == 0 ? rig.truth_a : rig.truth_b;
    const calib::StripeCalibrationResult& c = r.cameras[k];
    SCOPED_TRACE("camera " + std::to_string(k + 1));
    EXPECT_LT(position_error(c, truth), 0.05);
    EXPECT_LT(rotation_error(c, truth), 0.01 * kDeg);
    EXPECT_LT(std::acos(std::min(
                  1.0, c.geometry.axis_direction_cell.dot(truth.axis_direction_cell.normalized()))),
              0.01 * kDeg);
    EXPECT_LT(c.rms_mm, 0.01);
    // Three rounds of its own and the fourth with the piercing points averaged.
    ASSERT_EQ(c.rounds.size(), 4u);
    EXPECT_LT(c.rounds.back().corner_rms_mm, 0.05);
    for (const std::size_t n : c.rounds.back().plane_points) EXPECT_GT(n, 200u);
    // The camera on the far side kept its own baseline.
    EXPECT_EQ(c.geometry.ranger.baseline_mm, truth.ranger.baseline_mm);
  }
  // The start of b was off by a's perturbation and its own frame of the plane.
  EXPECT_GT((other_side_camera(hal::StripeCellGeometry{}, Eigen::Isometry3d::Identity())
                 .ranger_position_cell_mm -
             rig.truth_b.ranger_position_cell_mm)
                .norm(),
            5.0);
}

INSTANTIATE_TEST_SUITE_P(Perturbed, StripeRigSeeds, ::testing::Values(1u, 2u));

TEST(StripeRig, ReportsPerCameraCovariancesThatMatchTheNoise) {
  NormalisedErrors e;
  for (const std::uint64_t seed : {21u, 22u, 23u}) {
    const Rig rig = two_sided_rig(7, {.sigma_mm = 0.06, .seed = seed});
    const calib::StripeRigResult r = calibrate_rig(rig.a, rig.b);
    ASSERT_TRUE(r.ok) << r.reason;
    e.add(r.cameras[0], rig.truth_a);
    e.add(r.cameras[1], rig.truth_b);
  }
  // A factor of 1.5 in sigma is 2.25 in the mean squared normalised error.
  EXPECT_GT(e.mean(), 1.0 / 2.25);
  EXPECT_LT(e.mean(), 2.25);
}

// The far camera's frame turned over (its x and y reversed, as a camera mounted facing the
// other way reports): the in-plane map of the refinement flips, and both come back.
TEST(StripeRig, AFarCameraWithItsFrameTurnedOverIsRecovered) {
  const hal::StripeCellGeometry nominal;
  const hal::StripeCellGeometry truth_a = perturbed_cell(nominal, 4);
  Eigen::Isometry3d flip = Eigen::Isometry3d::Identity();
  flip.linear() = Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Isometry3d P = flip * b_in_a();
  const hal::StripeCellGeometry truth_b = other_side_camera(truth_a, P);
  EXPECT_GT(truth_b.ranger.baseline_mm, 0.0);  // its +y: the other side of the plane
  const Sweep a = stripe_cube_sweep(truth_a, {}, 2.0, cube_between_cameras());
  const Sweep b = other_side_sweep(truth_a, P, {}, 2.0, cube_between_cameras());
  calib::StripeRigInput in;
  in.cameras.push_back({a.profiles, a.axis, nominal});
  in.cameras.push_back({b.profiles, b.axis, other_side_camera(nominal, flip)});
  in.T_table_cube = cube_between_cameras();
  const calib::StripeRigResult r = calib::calibrate_stripe_rig(in);
  ASSERT_TRUE(r.ok) << r.reason;
  for (std::size_t k = 0; k < 2; ++k) {
    const hal::StripeCellGeometry& truth = k == 0 ? truth_a : truth_b;
    SCOPED_TRACE("camera " + std::to_string(k + 1));
    EXPECT_LT(position_error(r.cameras[k], truth), 0.05);
    EXPECT_LT(rotation_error(r.cameras[k], truth), 0.01 * kDeg);
  }
}

TEST(StripeRig, ACameraThatMissesTheCubeIsNamed) {
  const Rig rig = two_sided_rig(3, {});
  Sweep away = rig.b;
  for (double& s : away.axis) s += 1000.0;  // its profiles claim a part of the axis far off
  for (hal::RangerProfile& p : away.profiles) {
    std::fill(p.z_mm.begin(), p.z_mm.end(), std::numeric_limits<float>::quiet_NaN());
  }
  const calib::StripeRigResult r = calibrate_rig(rig.a, away);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.reason.rfind("camera 2: ", 0), 0u) << r.reason;
}

}  // namespace stripe_rig_test
}  // namespace rangefit::test
