#include "detect/object/superquadric.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace rangefit {
namespace superquadric_test {

Superquadric make(double a1, double a2, double a3, double e1, double e2, double kx = 0.0,
                  double ky = 0.0) {
  return Superquadric{a1, a2, a3, e1, e2, kx, ky};
}

std::vector<Superquadric> table_5_2() {
  return {make(30, 30, 50, 0.1, 1.0), make(25, 25, 50, 0.1, 0.1), make(50, 50, 50, 1.0, 1.0),
          make(20, 20, 40, 0.1, 1.0, -1.0, -1.0), make(10, 20, 30, 2.0, 2.0, 0.5, -0.3)};
}

TEST(Superquadric, SurfacePointsHaveMetricOne) {
  for (const Superquadric& sq : table_5_2()) {
    for (double eta = -1.5; eta <= 1.5; eta += 0.25) {
      for (double omega = -3.1; omega < 3.1; omega += 0.4) {
        const Eigen::Vector3d p = surface_point(sq, eta, omega);
        EXPECT_NEAR(metric(sq, p), 1.0, 1e-9) << sq.eps1 << " " << eta << " " << omega;
        EXPECT_NEAR(inside_outside(sq, p), 1.0, 1e-8);
      }
    }
  }
}

TEST(Superquadric, SignTellsInsideFromOutside) {
  const Superquadric cylinder = make(30, 30, 50, 0.1, 1.0);
  EXPECT_LT(metric(cylinder, {0, 0, 0}), 1.0);
  EXPECT_LT(metric(cylinder, {25, 0, 40}), 1.0);
  EXPECT_GT(metric(cylinder, {31, 0, 0}), 1.0);
  EXPECT_GT(metric(cylinder, {0, 0, 51}), 1.0);
  // The cone (taper -1) narrows towards +z: wide at the base, nothing near the tip.
  const Superquadric cone = make(20, 20, 40, 0.1, 1.0, -1.0, -1.0);
  EXPECT_LT(metric(cone, {35, 0, -35}), 1.0);
  EXPECT_GT(metric(cone, {5, 0, 38}), 1.0);
}

TEST(Superquadric, MetricGrowsLikeSquaredDistanceFarAway) {
  const Superquadric sphere = make(50, 50, 50, 1.0, 1.0);
  EXPECT_NEAR(metric(sphere, {100, 0, 0}), 4.0, 1e-12);
  const Superquadric box = make(25, 25, 50, 0.1, 0.1);
  EXPECT_NEAR(metric(box, {0, 0, 500}), 100.0, 1e-9);
}

TEST(Superquadric, FiniteOnAxisAtPolesCentreAndFarAway) {
  const std::vector<Eigen::Vector3d> probes = {
      {0, 0, 0}, {0, 0, 50}, {0, 0, -1e-300}, {1e-300, 0, 0}, {1e200, 1e200, 1e200},
      {0, 0, 1e250}, {-1e-8, 1e-8, 0}, {5, -5, 40}, {0, 0, 1e308}};
  for (const Superquadric& sq : table_5_2()) {
    for (double e1 : {0.1, 0.5, 1.0, 2.0}) {
      for (double e2 : {0.1, 0.7, 1.0, 2.0}) {
        Superquadric s = sq;
        s.eps1 = e1;
        s.eps2 = e2;
        for (const Eigen::Vector3d& p : probes) {
          Eigen::Vector3d g;
          const double v = metric_and_gradient(s, p, g);
          EXPECT_TRUE(std::isfinite(v)) << p.transpose();
          EXPECT_GE(v, 0.0);
          EXPECT_TRUE(g.allFinite()) << p.transpose();
          EXPECT_TRUE(std::isfinite(inside_outside(s, p)));
        }
      }
    }
  }
}

TEST(Superquadric, GradientMatchesFiniteDifferences) {
  for (const Superquadric& sq : table_5_2()) {
    for (const Eigen::Vector3d& p : {Eigen::Vector3d(12, -7, 20), Eigen::Vector3d(-40, 3, -10),
                                     Eigen::Vector3d(3, 25, 33)}) {
      Eigen::Vector3d g;
      metric_and_gradient(sq, p, g);
      for (int i = 0; i < 3; ++i) {
        Eigen::Vector3d d = Eigen::Vector3d::Zero();
        d[i] = 1e-5;
        const double fd = (metric(sq, p + d) - metric(sq, p - d)) / 2e-5;
        EXPECT_NEAR(g[i], fd, 1e-5 * std::max(1.0, std::abs(fd))) << i << " " << p.transpose();
      }
    }
  }
}

TEST(Superquadric, ValidityChecksRanges) {
  EXPECT_TRUE(make(1, 2, 3, 0.1, 2.0, -1.0, 1.0).valid());
  EXPECT_FALSE(make(0, 2, 3, 1, 1).valid());
  EXPECT_FALSE(make(1, 2, 3, 0.05, 1).valid());
  EXPECT_FALSE(make(1, 2, 3, 1, 2.5).valid());
  EXPECT_FALSE(make(1, 2, 3, 1, 1, 1.5).valid());
  EXPECT_FALSE(make(1, std::nan(""), 3, 1, 1).valid());
}

TEST(Superquadric, BoundsContainTheSurface) {
  for (const Superquadric& sq : table_5_2()) {
    const Eigen::AlignedBox3d box = part_bounds(sq);
    for (double eta = -1.57; eta <= 1.57; eta += 0.1) {
      for (double omega = -3.14; omega < 3.14; omega += 0.1) {
        EXPECT_TRUE(box.contains(surface_point(sq, eta, omega)));
      }
    }
  }
}

// The support along a direction is the largest m . x over the surface: no surface point reaches
// past it, and a dense sampling comes within a few tenths of a millimetre of it. A box's is
// a1 |mx| + a2 |my| + a3 |mz| (up to its rounded edges), an ellipsoid's sqrt(sum (a_i m_i)^2).
TEST(Superquadric, SupportIsTheFarthestReachOfTheSurface) {
  const std::vector<Eigen::Vector3d> directions = {
      Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 0),
      Eigen::Vector3d(0.3, -0.5, 0.8).normalized(), Eigen::Vector3d(-0.9, 0.2, -0.1).normalized()};
  for (const Superquadric& sq : table_5_2()) {
    if (sq.kx != 0.0 || sq.ky != 0.0) continue;
    for (const Eigen::Vector3d& m : directions) {
      double reach = -INFINITY;
      for (double eta = -1.5708; eta <= 1.5708; eta += 0.002) {
        for (double omega = -3.1416; omega < 3.1416; omega += 0.004) {
          reach = std::max(reach, m.dot(surface_point(sq, eta, omega)));
        }
      }
      const double h = support(sq, m);
      EXPECT_LE(reach, h + 1e-6) << sq.eps1 << " " << sq.eps2 << " " << m.transpose();
      EXPECT_GT(reach, h - 0.3) << sq.eps1 << " " << sq.eps2 << " " << m.transpose();
    }
  }
  const Eigen::Vector3d m = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  EXPECT_NEAR(
      support(make(10, 20, 30, 1, 1), m),
      std::sqrt(std::pow(10 * m.x(), 2) + std::pow(20 * m.y(), 2) + std::pow(30 * m.z(), 2)), 1e-9);
  // Sharp-edged (eps -> 0) the box's own: at eps 0.1 its edges round it off by a few per cent.
  const double box = 25 * std::abs(m.x()) + 25 * std::abs(m.y()) + 50 * std::abs(m.z());
  EXPECT_NEAR(support(make(25, 25, 50, 0.1, 0.1), m), box, 0.05 * box);
  EXPECT_LT(support(make(25, 25, 50, 0.1, 0.1), m), box);
}

TEST(Superquadric, TaperedSupportIsTheFarthestReachOfTheTaperedSurface) {
  const std::vector<Eigen::Vector3d> directions = {Eigen::Vector3d(0, 0, 1),
                                                   Eigen::Vector3d(0, 0, -1),
                                                   Eigen::Vector3d(1, 0, 0),
                                                   Eigen::Vector3d(0.3, -0.5, 0.8).normalized(),
                                                   Eigen::Vector3d(-0.9, 0.2, -0.1).normalized(),
                                                   Eigen::Vector3d(0.6, 0.1, -0.8).normalized()};
  std::vector<Superquadric> shapes = table_5_2();
  shapes.push_back(make(20, 30, 40, 0.3, 0.6, 0.4, -0.7));
  shapes.push_back(make(15, 15, 35, 1.0, 1.0, -0.5, 0.5));
  for (const Superquadric& sq : shapes) {
    std::vector<double> reach(directions.size(), -INFINITY);
    for (double eta = -1.5708; eta <= 1.5708; eta += 0.002) {
      for (double omega = -3.1416; omega < 3.1416; omega += 0.004) {
        const Eigen::Vector3d p = surface_point(sq, eta, omega);
        for (std::size_t k = 0; k < directions.size(); ++k) {
          reach[k] = std::max(reach[k], directions[k].dot(p));
        }
      }
    }
    for (std::size_t k = 0; k < directions.size(); ++k) {
      const double h = tapered_support(sq, directions[k]);
      EXPECT_LE(reach[k], h + 1e-6)
          << sq.eps1 << " " << sq.eps2 << " " << directions[k].transpose();
      EXPECT_GT(reach[k], h - 0.3) << sq.eps1 << " " << sq.eps2 << " " << directions[k].transpose();
    }
  }
  // The fig. 5.18 cone (apex at +z, base radius 2 a1 at -z) stands on its base and reaches its
  // apex straight up; sideways its base rim, rounded off by eps1 0.1; untapered,
  // tapered_support is support.
  const Superquadric cone = make(20, 20, 40, 0.1, 1.0, -1.0, -1.0);
  EXPECT_NEAR(tapered_support(cone, Eigen::Vector3d(0, 0, -1)), 40.0, 0.05);
  EXPECT_NEAR(tapered_support(cone, Eigen::Vector3d(0, 0, 1)), 40.0, 0.05);
  EXPECT_NEAR(tapered_support(cone, Eigen::Vector3d(1, 0, 0)), 38.15, 0.05);
  const Eigen::Vector3d m = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  EXPECT_EQ(tapered_support(make(10, 20, 30, 0.4, 0.7), m), support(make(10, 20, 30, 0.4, 0.7), m));
}

}  // namespace superquadric_test
}  // namespace rangefit
