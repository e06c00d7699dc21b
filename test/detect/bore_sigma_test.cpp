// The refined cylinder's standard errors (BoreResult::sigma_axis, sigma_radius): the bound the
// fit's own covariance puts on how well the scan determines a bore. On a small blind bore at the
// CSS's density (a few hundred one-sided wall points over a short wall) the axis is determined
// only to a few tenths of a degree; the reported sigma has to say so, and has to match the
// errors the detector actually makes over many scans.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "detect/bore/bore_detector.hpp"
#include "detect/bore/cylinder_lsf.hpp"
#include "test/detect/bore_test_cases.hpp"
#include "test/support/synthetic_bore.hpp"

namespace rangefit {
namespace bore_sigma_test {

// A 4 mm blind bore, 3 mm deep, at the CSS's density (two interleaved passes at 0.15 mm).
sim::SyntheticBoreScan small_blind_bore(std::uint64_t seed, double noise = 0.06) {
  sim::SyntheticBoreOptions o;
  o.radius = 2.0;
  o.depth = 3.0;
  o.spacing = 0.15;
  o.passes = 2;
  o.march_step = 0.1;
  o.noise_sigma = noise;
  o.seed = seed;
  o.T_world_part = test::random_pose(seed);
  return sim::make_synthetic_bore(o);
}

BoreResult detect(const sim::SyntheticBoreScan& scan, std::uint64_t seed) {
  BoreOptions o;
  o.view_dir = scan.truth.view_dir;
  return detect_bore(scan.cloud, test::perturbed_prior(scan.truth, seed), o);
}

// Over many scans the rms axis and radius errors are what the reported sigmas predict (an rms
// over 20 scans is within about +-30 % of the true one).
TEST(BoreSigma, SmallBlindBoreSigmaMatchesTheErrorsOverManyScans) {
  double e_axis = 0.0, s_axis = 0.0, e_radius = 0.0, s_radius = 0.0;
  constexpr int kScans = 20;
  for (int i = 0; i < kScans; ++i) {
    const std::uint64_t seed = 300 + static_cast<std::uint64_t>(i);
    const auto scan = small_blind_bore(seed);
    const BoreResult r = detect(scan, seed);
    ASSERT_TRUE(r.found) << to_string(r.reason) << " seed " << seed;
    ASSERT_TRUE(r.refined);
    ASSERT_GT(r.sigma_axis, 0.0);
    ASSERT_GT(r.sigma_radius, 0.0);
    ASSERT_GT(r.sigma_offset, 0.0);
    const double a = std::acos(std::min(1.0, std::abs(r.axis.dot(scan.truth.axis))));
    e_axis += a * a;
    s_axis += r.sigma_axis * r.sigma_axis;
    e_radius += std::pow(r.radius - scan.truth.radius, 2);
    s_radius += r.sigma_radius * r.sigma_radius;
  }
  const double axis_ratio = std::sqrt(e_axis / s_axis);
  const double radius_ratio = std::sqrt(e_radius / s_radius);
  EXPECT_GT(axis_ratio, 0.6);
  EXPECT_LT(axis_ratio, 1.5);
  EXPECT_GT(radius_ratio, 0.6);
  EXPECT_LT(radius_ratio, 1.5);
  // A few hundred wall points over a 3 mm wall: tenths of a degree, not hundredths.
  const double rms_sigma_deg = std::sqrt(s_axis / kScans) * 180.0 / std::numbers::pi;
  EXPECT_GT(rms_sigma_deg, 0.1);
  EXPECT_LT(rms_sigma_deg, 0.5);
}

// The bound follows the noise: half the range noise, about half the axis sigma.
TEST(BoreSigma, AxisSigmaFollowsTheNoise) {
  const std::uint64_t seed = 341;
  const BoreResult noisy = detect(small_blind_bore(seed, 0.06), seed);
  const BoreResult quiet = detect(small_blind_bore(seed, 0.03), seed);
  ASSERT_TRUE(noisy.found && quiet.found);
  const double ratio = quiet.sigma_axis / noisy.sigma_axis;
  EXPECT_GT(ratio, 0.35);
  EXPECT_LT(ratio, 0.7);
}

// cylinder_sigma on exact points of a known arc: a longer wall or more points, a smaller sigma,
// in the proportions least squares predicts (tilt ~ 1 / (sqrt(n) length), radius ~ 1 / sqrt(n)).
TEST(BoreSigma, CylinderSigmaScalesWithPointsAndWallLength) {
  const auto arc = [](int n, double length) {
    std::vector<Eigen::Vector3d> pts;
    std::uint64_t state = 12345;
    const auto noise = [&] {  // a fixed, small, zero-mean pseudo-random residual
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      return 0.05 * (static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5);
    };
    for (int i = 0; i < n; ++i) {
      const double phi = 2.0 * (static_cast<double>(i % 37) / 36.0 - 0.5);  // +-1 rad
      const double h = length * (static_cast<double>(i % 101) / 100.0);
      const double r = 3.0 + noise();
      pts.emplace_back(r * std::cos(phi), r * std::sin(phi), h);
    }
    return pts;
  };
  const Cylinder c{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 3.0};
  const CylinderSigma base = cylinder_sigma(arc(4000, 3.0), c, 0.0);
  const CylinderSigma more = cylinder_sigma(arc(16000, 3.0), c, 0.0);
  const CylinderSigma longer = cylinder_sigma(arc(4000, 6.0), c, 0.0);
  ASSERT_TRUE(base.valid && more.valid && longer.valid);
  EXPECT_NEAR(more.axis / base.axis, 0.5, 0.05);
  EXPECT_NEAR(more.radius / base.radius, 0.5, 0.05);
  EXPECT_NEAR(longer.axis / base.axis, 0.5, 0.05);
  EXPECT_NEAR(base.rms, 0.05 / std::sqrt(12.0), 0.002);  // uniform residuals of width 0.05
  // Points beyond the trim do not count.
  EXPECT_LT(cylinder_sigma(arc(4000, 3.0), c, 0.02).points, 4000u);
}

}  // namespace bore_sigma_test
}  // namespace rangefit
