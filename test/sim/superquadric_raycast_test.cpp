#include "sim/superquadric_raycast.hpp"
#include "test/support/ordered_draws.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace rangefit::sim {
namespace superquadric_raycast_test {

Eigen::Isometry3d pose(const Eigen::Vector3d& t, const Eigen::Vector3d& axis, double angle) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  T.translation() = t;
  return T;
}

TEST(SuperquadricRaycast, HitsSphereAtAnalyticDistance) {
  const Superquadric sphere{50, 50, 50, 1.0, 1.0, 0.0, 0.0};
  const auto t =
      intersect_superquadric(sphere, pose({0, 0, 0}, {0, 0, 1}, 0.0), {0, 0, 200}, {0, 0, -1}, 1e9);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, 150.0, 1e-6);
}

TEST(SuperquadricRaycast, MissesWhenRayPassesBesideOrStopsShort) {
  const Superquadric box{25, 25, 50, 0.1, 0.1, 0.0, 0.0};
  const Eigen::Isometry3d T = pose({0, 0, 0}, {0, 0, 1}, 0.0);
  EXPECT_FALSE(intersect_superquadric(box, T, {30, 30, 200}, {0, 0, -1}, 1e9).has_value());
  EXPECT_FALSE(intersect_superquadric(box, T, {0, 0, 200}, {0, 0, -1}, 100.0).has_value());
  EXPECT_FALSE(intersect_superquadric(box, T, {0, 0, 200}, {0, 0, 1}, 1e9).has_value());
}

TEST(SuperquadricRaycast, RejectsInvalidInputWithoutCrashing) {
  const Superquadric bad{0, 25, 50, 0.1, 0.1, 0.0, 0.0};
  const Superquadric ok{25, 25, 50, 0.1, 0.1, 0.0, 0.0};
  const Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  EXPECT_FALSE(intersect_superquadric(bad, T, {0, 0, 200}, {0, 0, -1}, 1e9));
  EXPECT_FALSE(intersect_superquadric(ok, T, {0, 0, 200}, {0, 0, 0}, 1e9));
  EXPECT_FALSE(intersect_superquadric(ok, T, {0, 0, NAN}, {0, 0, -1}, 1e9));
}

TEST(SuperquadricRaycast, HitPointsLieOnTheSurfaceForAllShapes) {
  const std::vector<Superquadric> models = {{30, 30, 50, 0.1, 1.0, 0.0, 0.0},
                                            {25, 25, 50, 0.1, 0.1, 0.0, 0.0},
                                            {50, 50, 50, 1.0, 1.0, 0.0, 0.0},
                                            {20, 20, 40, 0.1, 1.0, -1.0, -1.0},
                                            {20, 10, 30, 2.0, 2.0, 0.4, -0.3}};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const Superquadric& sq : models) {
    const Eigen::Isometry3d T = pose({10, -20, 30}, {1, 2, 3}, 0.7);
    int hits = 0;
    for (int i = 0; i < 300; ++i) {
      const double oy = u(rng), ox = u(rng);  // in the order of the recorded data
      const Eigen::Vector3d origin(ox * 300, oy * 300, 400);
      const Eigen::Vector3d target = T.translation() + test::draw3(u, rng) * sq.max_size();
      const Eigen::Vector3d dir = (target - origin).normalized();
      const auto t = intersect_superquadric(sq, T, origin, dir, 1e9);
      if (!t) continue;
      ++hits;
      const Eigen::Vector3d p = origin + *t * dir;
      EXPECT_NEAR(metric_world(sq, T, p), 1.0, 1e-7);
      // Nothing of the part lies between the origin and the hit: it is the first entry.
      for (double s = 0.02; s < 1.0; s += 0.02) {
        EXPECT_GT(metric_world(sq, T, origin + s * *t * dir), 1.0 - 1e-9);
      }
    }
    EXPECT_GT(hits, 30);  // rays aimed into the bounding cube; thin parts are missed often
  }
}

TEST(SuperquadricRaycast, NormalPointsOutwards) {
  const Superquadric sphere{50, 50, 50, 1.0, 1.0, 0.0, 0.0};
  const Eigen::Isometry3d T = pose({5, 5, 5}, {0, 0, 1}, 0.0);
  const Eigen::Vector3d n = superquadric_normal(sphere, T, {5, 5, 55});
  EXPECT_NEAR(n.z(), 1.0, 1e-9);
}

TEST(SceneRenderer, EmptySceneGivesOnlyTheTable) {
  SceneView view;
  view.width = 40;
  view.height = 30;
  const RenderedScene s = render_scene({}, view);
  EXPECT_GT(s.cloud.size(), 0u);
  for (const auto& p : s.cloud.points) EXPECT_NEAR(p.z(), 0.0, 1e-9);
  view.table = false;
  EXPECT_TRUE(render_scene({}, view).cloud.empty());
}

TEST(SceneRenderer, PartOccludesTheTableAndIsLabelled) {
  SceneView view;
  view.width = 80;
  view.height = 60;
  const std::vector<ScenePart> parts = {
      {"sphere", Superquadric{50, 50, 50, 1, 1, 0, 0}, pose({150, 100, 50}, {0, 0, 1}, 0.0)}};
  const RenderedScene s = render_scene(parts, view);
  int on_sphere = 0;
  for (std::size_t i = 0; i < s.cloud.size(); ++i) {
    if (s.label[i] == 0) {
      ++on_sphere;
      EXPECT_NEAR(metric_world(parts[0].model, parts[0].T_world_part, s.cloud.points[i]), 1.0,
                  1e-7);
    }
  }
  EXPECT_GT(on_sphere, 50);
  EXPECT_EQ(s.cloud.grid.rows, 60);
}

TEST(SceneRenderer, NoiseIsSeeded) {
  SceneView view;
  view.width = 20;
  view.height = 20;
  view.noise_sigma_mm = 1.0;
  const RenderedScene a = render_scene({}, view);
  const RenderedScene b = render_scene({}, view);
  view.noise_seed = 2;
  const RenderedScene c = render_scene({}, view);
  ASSERT_EQ(a.cloud.size(), b.cloud.size());
  EXPECT_EQ(a.cloud.points[5], b.cloud.points[5]);
  EXPECT_NE(a.cloud.points[5], c.cloud.points[5]);
}

}  // namespace superquadric_raycast_test
}  // namespace rangefit::sim
