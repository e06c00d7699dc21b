#include "detect/object/pose_fit.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <random>
#include <vector>

#include "test/detect/object_scenes.hpp"
#include "test/support/ordered_draws.hpp"

namespace rangefit {
namespace pose_fit_test {

// Points on the visible half (x > 0 in the part frame) of a posed part.
std::vector<Eigen::Vector3d> surface_samples(const Superquadric& sq, const Eigen::Isometry3d& T,
                                             int n, std::uint64_t seed, double sigma = 0.0) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> eta(-1.5, 1.5), omega(-1.4, 1.4);
  std::normal_distribution<double> noise(0.0, sigma > 0.0 ? sigma : 1.0);
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < n; ++i) {
    const double w = omega(rng), e = eta(rng);  // in the order of the recorded data
    Eigen::Vector3d p = T * surface_point(sq, e, w);
    if (sigma > 0.0) p += sigma * test::draw3(noise, rng);
    out.push_back(p);
  }
  return out;
}

TEST(PoseFit, RecoversAPerturbedPoseExactly) {
  const Superquadric cyl = test::cylinder_model();
  const Eigen::Isometry3d truth = test::pose_from_axis({100, 50, 60}, {0.3, -0.2, 0.9});
  const auto pts = surface_samples(cyl, truth, 200, 3);
  Eigen::Isometry3d start = truth;
  start.translation() += Eigen::Vector3d(3, -2, 2);
  start.linear() = start.linear() *
                   Eigen::AngleAxisd(0.1, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  PoseFitOptions o;
  o.max_iterations = 50;
  const PoseFitResult r = fit_pose(cyl, pts, start, o);
  ASSERT_TRUE(r.ok());
  EXPECT_LT((r.T_world_part.translation() - truth.translation()).norm(), 1e-4);
  EXPECT_GT(std::abs(r.T_world_part.linear().col(2).dot(truth.linear().col(2))), 1.0 - 1e-9);
  EXPECT_LT(r.measure, 1e-6);
  // M at the start, as the detector's refinement compares it with the result.
  EXPECT_NEAR(r.initial_measure, measure_of_fit(cyl, start, pts), 1e-12);
  EXPECT_GT(r.initial_measure, 0.01);
}

TEST(PoseFit, HandlesAnAxisPointingStraightUpWithoutGimbalLock) {
  const Superquadric box = test::box_model();
  const Eigen::Isometry3d truth = test::pose_from_axis({0, 0, 50}, {0, 0, 1}, 0.4);
  const auto pts = surface_samples(box, truth, 150, 4);
  Eigen::Isometry3d start = truth;
  start.linear() =
      start.linear() * Eigen::AngleAxisd(0.15, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const PoseFitResult r = fit_pose(box, pts, start, {.max_iterations = 50});
  EXPECT_LT((r.T_world_part.translation() - truth.translation()).norm(), 1e-3);
  EXPECT_GT(r.T_world_part.linear().col(2).dot(truth.linear().col(2)), 1.0 - 1e-8);
}

TEST(PoseFit, MomentInitialisationFindsTheCylinderFromOneSide) {
  const Superquadric cyl = test::cylinder_model();
  const Eigen::Isometry3d truth = test::pose_from_axis({20, 30, 40}, {0.2, 0.1, 1.0});
  const auto pts = surface_samples(cyl, truth, 60, 5, 0.05);
  MomentInitOptions init;
  init.full_iterations = 60;
  const PoseFitResult r = fit_pose_from_moments(cyl, pts, init);
  ASSERT_TRUE(r.ok());
  EXPECT_LT((r.T_world_part.translation() - truth.translation()).norm(), 1.0);
  EXPECT_GT(std::abs(r.T_world_part.linear().col(2).dot(truth.linear().col(2))), std::cos(0.05));
}

TEST(PoseFit, StopsOnTheGradientRuleAtTheSolution) {
  const Superquadric sphere = test::sphere_model();
  const Eigen::Isometry3d truth = test::pose_from_axis({1, 2, 3}, {0, 0, 1});
  const auto pts = surface_samples(sphere, truth, 50, 6);
  const PoseFitResult r = fit_pose(sphere, pts, truth);
  EXPECT_NE(r.termination, FitTermination::kMaxIterations);
  EXPECT_LE(r.iterations, 2);
}

TEST(PoseFit, EmptyTooFewAndBadInputAreReportedNotFitted) {
  const Superquadric sphere = test::sphere_model();
  EXPECT_EQ(fit_pose(sphere, {}, Eigen::Isometry3d::Identity()).termination,
            FitTermination::kTooFewPoints);
  std::vector<Eigen::Vector3d> pts(3, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(fit_pose(sphere, pts, Eigen::Isometry3d::Identity()).termination,
            FitTermination::kTooFewPoints);
  pts.assign(10, Eigen::Vector3d(NAN, 0, 0));
  EXPECT_EQ(fit_pose(sphere, pts, Eigen::Isometry3d::Identity()).termination,
            FitTermination::kInvalidInput);
  Superquadric bad = sphere;
  bad.eps1 = 5.0;
  EXPECT_FALSE(
      fit_pose_from_moments(bad, surface_samples(sphere, Eigen::Isometry3d::Identity(), 20, 1))
          .ok());
  EXPECT_EQ(measure_of_fit(sphere, Eigen::Isometry3d::Identity(), {}), 0.0);
}

}  // namespace pose_fit_test
}  // namespace rangefit
