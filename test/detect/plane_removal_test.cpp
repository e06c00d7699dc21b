#include "detect/common/plane_removal.hpp"

#include <gtest/gtest.h>

#include "test/detect/object_scenes.hpp"

namespace rangefit {
namespace plane_removal_test {

TEST(PlaneRemoval, RemovesTheTableAndKeepsTheObjects) {
  const test::Scene s = test::fig_5_18_scene(0.0, 1, 0.4);
  const PlaneRemovalResult r = remove_dominant_plane(s.rendered.cloud.points);
  ASSERT_TRUE(r.removed());
  EXPECT_GT(std::abs(r.plane.normal.z()), 0.9999);
  EXPECT_NEAR(r.plane.point.z(), 0.0, 1e-6);
  std::size_t table = 0, objects_kept = 0, objects = 0;
  for (std::size_t i = 0; i < s.rendered.label.size(); ++i) {
    if (s.rendered.label[i] < 0)
      ++table;
    else
      ++objects;
  }
  for (std::uint32_t i : r.remaining) {
    EXPECT_GE(s.rendered.label[i], 0) << "a table point was kept";
    if (s.rendered.label[i] >= 0) ++objects_kept;
  }
  EXPECT_EQ(r.plane_points, table + (objects - objects_kept));
  EXPECT_GT(static_cast<double>(objects_kept), 0.97 * static_cast<double>(objects));
}

TEST(PlaneRemoval, KeepsEverythingWhenNoPlaneDominates) {
  test::Scene s = test::fig_5_18_scene(0.0, 1, 0.4);
  std::vector<Eigen::Vector3d> objects;
  for (std::size_t i = 0; i < s.rendered.label.size(); ++i) {
    if (s.rendered.label[i] >= 0) objects.push_back(s.rendered.cloud.points[i]);
  }
  const PlaneRemovalResult r = remove_dominant_plane(objects);
  EXPECT_FALSE(r.removed());
  EXPECT_EQ(r.remaining.size(), objects.size());
}

TEST(PlaneRemoval, EmptyAndTinyCloudsAreLeftAlone) {
  EXPECT_EQ(remove_dominant_plane({}).reason, PlaneRemovalReason::kTooFewPoints);
  std::vector<Eigen::Vector3d> three = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const PlaneRemovalResult r = remove_dominant_plane(three);
  EXPECT_FALSE(r.removed());
  EXPECT_EQ(r.remaining.size(), 3u);
}

}  // namespace plane_removal_test
}  // namespace rangefit
