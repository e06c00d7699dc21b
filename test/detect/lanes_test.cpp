#include "detect/common/lanes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "detect/object/superquadric.hpp"
#include "detect/object/superquadric_eval.hpp"
#include "test/detect/object_scenes.hpp"
#include "test/support/ordered_draws.hpp"

namespace rangefit {
namespace lanes_test {

using lanes::V4d;

TEST(Lanes, PowMatchesStdPowToTheLastBits) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> log_x(std::log(1e-300), std::log(1e6));
  std::uniform_real_distribution<double> expo(0.05, 20.0);
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const double x = std::exp(log_x(rng)), e = expo(rng);
    const double want = std::pow(x, e);
    if (want < 1e-300 || want > 1e300) continue;  // outside the clamped exponent range
    worst = std::max(worst, std::abs(lanes::pow_positive(x, e) - want) / want);
  }
  // exp(e log x) amplifies log's absolute error by e log x (up to ~300 here).
  EXPECT_LT(worst, 1e-13);
  // The ranges the metric uses (x in [0, 1 + 2^20], e in [0.05, 20]) with small e log x.
  EXPECT_NEAR(lanes::pow_positive(2.0, 0.5), std::sqrt(2.0), 4e-16);
  EXPECT_NEAR(lanes::pow_positive(1.0, 0.1), 1.0, 1e-16);
  EXPECT_NEAR(lanes::pow_positive(1025.0, 0.1), std::pow(1025.0, 0.1), 1e-15);
}

TEST(Lanes, PowOfZeroTinyAndNaNIsZero) {
  EXPECT_EQ(lanes::pow_positive(0.0, 0.1), 0.0);
  EXPECT_EQ(lanes::pow_positive(1e-310, 2.5), 0.0);  // subnormal
  EXPECT_EQ(lanes::pow_positive(std::nan(""), 0.5), 0.0);
}

TEST(Lanes, VectorLanesEqualTheScalar) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-100.0, 100.0);
  std::vector<double> xs = {0.0, 1e-300, 1.0, 2.0, 0.5};
  for (int i = 0; i < 400; ++i) xs.push_back(std::abs(u(rng)) + 1e-9);
  for (std::size_t i = 0; i + 4 <= xs.size(); i += 4) {
    const V4d x = {xs[i], xs[i + 1], xs[i + 2], xs[i + 3]};
    const V4d p = lanes::pow_positive(x, 0.37);
    for (int l = 0; l < 4; ++l) EXPECT_EQ(p[l], lanes::pow_positive(xs[i + l], 0.37));
  }
}

// The pose fit evaluates four points per lane vector; its values must be the scalar metric's.
TEST(Lanes, SuperquadricLanesEqualTheScalarMetric) {
  const std::vector<Superquadric> parts = {test::cylinder_model(),
                                           test::box_model(),
                                           test::sphere_model(),
                                           test::cone_model(),
                                           {10, 20, 30, 0.7, 1.3, 0.5, -0.3}};
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-80.0, 80.0);
  std::vector<Eigen::Vector3d> pts = {
      {0, 0, 0},     {0, 0, 50},  {1e200, 0, 0},  {std::nan(""), 1, 2},
      {0, 0, 1e308}, {0, 0, -40}, {1e-300, 0, 0}, {5, -5, 40}};
  for (int i = 0; i < 400; ++i) pts.push_back(test::draw3(u, rng));
  for (const Superquadric& sq : parts) {
    const SuperquadricMetric m(sq);
    for (std::size_t i = 0; i + 4 <= pts.size(); i += 4) {
      V4d x, y, z, gx, gy, gz;
      for (int l = 0; l < 4; ++l) {
        x[l] = pts[i + l].x();
        y[l] = pts[i + l].y();
        z[l] = pts[i + l].z();
      }
      const V4d v = m.evaluate<V4d, true>(x, y, z, &gx, &gy, &gz);
      for (int l = 0; l < 4; ++l) {
        Eigen::Vector3d g;
        const double want = m.value_and_gradient(pts[i + l], g);
        EXPECT_EQ(v[l], want) << pts[i + l].transpose();
        EXPECT_EQ(gx[l], g.x());
        EXPECT_EQ(gy[l], g.y());
        EXPECT_EQ(gz[l], g.z());
      }
    }
  }
}

TEST(Lanes, BatchValuesMatchThePointwiseMetric) {
  const SuperquadricMetric m(test::cone_model());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-60.0, 60.0);
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 103; ++i) pts.push_back(test::draw3(u, rng));  // not a multiple of 4
  const std::vector<std::uint32_t> idx = {5, 0, 102, 7, 7, 50, 1};
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(3, -4, 5);
  std::vector<double> out(idx.size(), -1.0);
  m.values(T, pts, idx, out);
  for (std::size_t k = 0; k < idx.size(); ++k) {
    const double want = m.value(T * pts[idx[k]]);
    EXPECT_NEAR(out[k], want, 1e-12 * std::max(1.0, want)) << k;
  }
  m.values(T, pts, {}, {});  // nothing to do, nothing touched
}

}  // namespace lanes_test
}  // namespace rangefit
