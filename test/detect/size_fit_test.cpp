// The free-size fit (detect/object/size_fit.hpp): the scale across and along a part's axis that
// its points want, with standard errors that say whether the points place it at all.
#include "detect/object/size_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "test/detect/object_scenes.hpp"
#include "test/support/ordered_draws.hpp"

namespace rangefit {
namespace size_fit_test {

// Points on the surface of `sq` posed at T that face the eye (a convex part hides only its own
// back), with Gaussian noise of sigma mm.
std::vector<Eigen::Vector3d> seen_from(const Superquadric& sq, const Eigen::Isometry3d& T,
                                       const Eigen::Vector3d& eye, double sigma,
                                       std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> eta(-1.5707, 1.5707), omega(-3.1415, 3.1415);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < 4000; ++i) {
    const double w = omega(rng), e = eta(rng);  // in the order of the recorded data
    const Eigen::Vector3d q = surface_point(sq, e, w);
    Eigen::Vector3d g;
    metric_and_gradient(sq, q, g);
    const Eigen::Vector3d p = T * q;
    if ((T.linear() * g).dot(eye - p) <= 0.0) continue;
    out.push_back(p + sigma * test::draw3(noise, rng));
  }
  return out;
}

Superquadric scaled(Superquadric sq, double across, double along) {
  sq.a1 *= across, sq.a2 *= across, sq.a3 *= along;
  return sq;
}

// A box posed tilted, seen from above and one side at 0.1 mm noise; the fit starts from the
// pose the model would take (2 mm and 2 deg off).
const Eigen::Isometry3d kTilted = test::pose_from_axis({40, -20, 70}, {0.3, -0.2, 0.9}, 0.4);
const Eigen::Vector3d kEye(300, -200, 600);

Eigen::Isometry3d off(const Eigen::Isometry3d& T) {
  Eigen::Isometry3d out = T;
  out.translation() += Eigen::Vector3d(1.5, -1.0, 1.0);
  out.linear() =
      out.linear() * Eigen::AngleAxisd(0.035, Eigen::Vector3d(1, 1, 0).normalized()).matrix();
  return out;
}

TEST(SizeFit, ReadsTheModelsOwnSizeAsOne) {
  const Superquadric box = test::box_model();
  const SizeFit f = fit_size(box, seen_from(box, kTilted, kEye, 0.1, 1), off(kTilted));
  ASSERT_TRUE(f.ok);
  // Well within the detector's 3 % (ObjectDetectOptions::max_size_deviation).
  EXPECT_NEAR(f.across, 1.0, 0.01);
  EXPECT_NEAR(f.along, 1.0, 0.01);
  EXPECT_LT(f.across_sigma, 0.005);
  EXPECT_LT(f.along_sigma, 0.005);
  EXPECT_LT((f.T_world_part.translation() - kTilted.translation()).norm(), 0.5);
  EXPECT_NEAR(f.rms_mm, f.model_rms_mm, 0.01);
}

// A look-alike 6 % longer and 4 % wider: the fit reads both, whatever the point count, and fits
// the points clearly better than the model's size does.
TEST(SizeFit, ReadsALookAlikesSizeAcrossAndAlongItsAxis) {
  const Superquadric box = test::box_model();
  const SizeFit f =
      fit_size(box, seen_from(scaled(box, 1.04, 1.06), kTilted, kEye, 0.1, 2), off(kTilted));
  ASSERT_TRUE(f.ok);
  EXPECT_NEAR(f.across, 1.04, 0.005);
  EXPECT_NEAR(f.along, 1.06, 0.005);
  EXPECT_LT(f.across_sigma, 0.005);
  EXPECT_LT(f.along_sigma, 0.005);
  EXPECT_LT(f.rms_mm, 0.5 * f.model_rms_mm);
}

// The top face alone says nothing of the size: a larger box set lower fits it as well. The
// standard errors say so instead of a number.
TEST(SizeFit, LeavesTheSizeOpenWhereOnlyOneFaceIsSeen) {
  const Superquadric box = test::box_model();
  const Eigen::Isometry3d standing = test::pose_from_axis({0, 0, 50}, {0, 0, 1});
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.1);
  std::vector<Eigen::Vector3d> top;
  for (double x = -15; x <= 15; x += 1) {
    for (double y = -15; y <= 15; y += 1) top.emplace_back(x, y, 100 + noise(rng));
  }
  const SizeFit f = fit_size(box, top, standing);
  ASSERT_TRUE(f.ok);
  // Several times the 0.005 by which the detector takes a scale as placed.
  EXPECT_GT(f.along_sigma, 0.02);
  EXPECT_GT(f.across_sigma, 0.02);
}

// A standing can seen from above shows its top and its wall, but not where it meets the table
// (the plane removal takes the points within a few millimetres of it): a longer can reaches into
// the table unseen, and its height is open until the table bounds it. Points of a real can, away
// from its rims (the model's rounded rims, which scale with it, would place the height by their
// shape alone). With the table, a can 5 % taller than the model reads 1.05.
TEST(SizeFit, TheTablePlacesAStandingCansHeight) {
  const Superquadric can = test::cylinder_model();  // radius 30, a3 = 50
  const double top = 2.0 * 1.05 * can.a3;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 0.1);
  std::vector<Eigen::Vector3d> pts;
  for (double r = 0.0; r <= 24.0; r += 1.5) {
    for (double phi = 0.0; phi < 6.28; phi += 0.1) {
      pts.emplace_back(r * std::cos(phi), r * std::sin(phi), top + noise(rng));
    }
  }
  for (double z = 5.0; z <= top - 8.0; z += 1.5) {
    for (double phi = -3.0; phi <= 0.0; phi += 0.05) {  // the half facing -y
      const double r = 30.0 + noise(rng);
      pts.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
    }
  }
  // The model's pose fitted by the top: 2.5 mm higher, floating 2.5 mm above the table.
  const Eigen::Isometry3d start = test::pose_from_axis({0, 0, top - can.a3}, {0, 0, 1});
  const SizeFit open = fit_size(can, pts, start);
  ASSERT_TRUE(open.ok);
  EXPECT_GT(open.along_sigma, 0.005);  // not placed, by the detector's measure
  SizeFitOptions o;
  o.support_plane = Eigen::Vector4d(0, 0, 1, 0);  // z = 0, normal up
  const SizeFit held = fit_size(can, pts, start, o);
  ASSERT_TRUE(held.ok);
  EXPECT_NEAR(held.along, 1.05, 0.005);
  EXPECT_LT(held.along_sigma, 0.005);
  EXPECT_NEAR(held.across, 1.0, 0.005);
}

// The pose alone at the model's size: the scales stay 1 and the pose comes back from 2 mm and
// 2 deg off.
TEST(SizeFit, AtAFixedSizeFitsThePoseAlone) {
  const Superquadric box = test::box_model();
  SizeFitOptions o;
  o.free_size = false;
  const SizeFit f = fit_size(box, seen_from(box, kTilted, kEye, 0.1, 4), off(kTilted), o);
  ASSERT_TRUE(f.ok);
  EXPECT_EQ(f.across, 1.0);
  EXPECT_EQ(f.along, 1.0);
  EXPECT_LT((f.T_world_part.translation() - kTilted.translation()).norm(), 0.3);
  EXPECT_GT(f.T_world_part.linear().col(2).dot(kTilted.linear().col(2)), std::cos(0.005));
}

TEST(SizeFit, TooFewOrNonFinitePointsAreNotOk) {
  const Superquadric box = test::box_model();
  std::vector<Eigen::Vector3d> pts = seen_from(box, kTilted, kEye, 0.1, 5);
  EXPECT_FALSE(fit_size(box, std::span(pts).first(8), kTilted).ok);
  pts[3].x() = std::nan("");
  EXPECT_FALSE(fit_size(box, pts, kTilted).ok);
  Superquadric invalid = box;
  invalid.a1 = -1.0;
  EXPECT_FALSE(fit_size(invalid, seen_from(box, kTilted, kEye, 0.1, 6), kTilted).ok);
}

}  // namespace size_fit_test
}  // namespace rangefit
