#include "detect/common/pca.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <random>
#include <vector>

namespace rangefit::pca {
namespace pca_test {

TEST(Pca, EmptyInputGivesZeroCentroidAndInvalidFits) {
  std::vector<Eigen::Vector3d> none;
  EXPECT_TRUE(centroid(none).isZero());
  EXPECT_TRUE(covariance(none, Eigen::Vector3d::Zero()).isZero());
  EXPECT_FALSE(fit_plane(none).valid);
  EXPECT_FALSE(fit_line(none).valid);
  Moments m;
  EXPECT_TRUE(m.covariance().isZero());
}

TEST(Pca, CovarianceUsesSampleNormalisation) {
  std::vector<Eigen::Vector3d> pts{{0, 0, 0}, {2, 0, 0}};
  const Eigen::Matrix3d c = covariance(pts, centroid(pts));
  EXPECT_DOUBLE_EQ(c(0, 0), 2.0);  // ((-1)^2 + 1^2) / (n - 1)
  Moments m;
  for (const auto& p : pts) m.add(p);
  EXPECT_TRUE(m.covariance().isApprox(c));
}

TEST(Pca, PlaneFitRecoversTiltedNoisyPlane) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  std::normal_distribution<double> noise(0.0, 0.01);
  const Eigen::Vector3d normal = Eigen::Vector3d(0.2, -0.3, 1.0).normalized();
  const Eigen::Vector3d e1 = normal.unitOrthogonal(), e2 = normal.cross(e1);
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 500; ++i) {
    const double n = noise(rng), b = u(rng), a = u(rng);  // the order of the recorded data
    pts.push_back(Eigen::Vector3d(1, 2, 3) + a * e1 + b * e2 + n * normal);
  }
  const Plane plane = fit_plane(pts);
  ASSERT_TRUE(plane.valid);
  EXPECT_GT(std::abs(plane.normal.dot(normal)), 0.99999);
  EXPECT_NEAR(plane.rms, 0.01, 0.002);
  EXPECT_NEAR((plane.point - Eigen::Vector3d(1, 2, 3)).dot(normal), 0.0, 0.005);
}

TEST(Pca, CollinearPointsHaveNoPlaneButALine) {
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 10; ++i) pts.push_back(Eigen::Vector3d(1, 1, 1) * i);
  EXPECT_FALSE(fit_plane(pts).valid);
  const Line line = fit_line(pts);
  ASSERT_TRUE(line.valid);
  EXPECT_GT(std::abs(line.direction.dot(Eigen::Vector3d(1, 1, 1).normalized())), 1.0 - 1e-12);
}

}  // namespace pca_test
}  // namespace rangefit::pca
