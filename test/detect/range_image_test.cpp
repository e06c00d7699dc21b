#include "detect/range_image.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "detect/kdtree.hpp"
#include "detect/object_coverage.hpp"
#include "test/detect/object_scenes.hpp"

namespace rangefit {
namespace {

// A 400 x 400 mm wall in the plane z = 0, 2 mm grid, seen from 500 mm above its centre.
std::vector<Eigen::Vector3d> wall() {
  std::vector<Eigen::Vector3d> pts;
  for (double x = -200; x <= 200; x += 2.0) {
    for (double y = -200; y <= 200; y += 2.0) pts.emplace_back(x, y, 0.0);
  }
  return pts;
}

const Eigen::Vector3d kEye(0, 0, 500);

TEST(RangeImage, TellsFreeSpaceFromOcclusionAndSurface) {
  const RangeImage img(wall(), kEye);
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.along({10, 20, 100}, 3.0), RayEvidence::kBehind);  // the wall was seen past it
  EXPECT_EQ(img.along({10, 20, 1.0}, 3.0), RayEvidence::kAt);
  EXPECT_EQ(img.along({10, 20, -100}, 3.0), RayEvidence::kInFront);  // hidden by the wall
  EXPECT_EQ(img.along({600, 0, 0}, 3.0), RayEvidence::kUnknown);     // outside the scan
  EXPECT_EQ(img.along({0, 0, 900}, 3.0), RayEvidence::kUnknown);     // behind the sensor
}

TEST(RangeImage, PointAtASilhouetteIsNotSeenPast) {
  // A 40 mm block 100 mm above the wall; a point on its edge sees block and wall in its pixel.
  std::vector<Eigen::Vector3d> pts;
  for (const Eigen::Vector3d& p : wall()) {
    if (std::abs(p.x()) > 12 || std::abs(p.y()) > 12) pts.push_back(p);  // the block's shadow
  }
  for (double x = -20; x <= 20; x += 1.0) {
    for (double y = -20; y <= 20; y += 1.0) pts.emplace_back(x, y, 100.0);
  }
  const RangeImage img(pts, kEye, 1.0);        // pixels of about one block point (1 mm)
  for (double off : {0.25, 0.5, 0.75, 1.0}) {  // just outside the edge: within a pixel of it
    EXPECT_NE(img.along({20 + off, 0, 100}, 3.0), RayEvidence::kBehind) << off;
    EXPECT_NE(img.along({0, -20 - off, 100}, 3.0), RayEvidence::kBehind) << off;
  }
  EXPECT_EQ(img.along({30, 0, 100}, 3.0), RayEvidence::kBehind);
}

TEST(RangeImage, EmptyOrNonFiniteInputGivesUnknown) {
  const RangeImage none({}, kEye);
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(none.along({0, 0, 0}, 3.0), RayEvidence::kUnknown);
  const std::vector<Eigen::Vector3d> bad = {{std::nan(""), 0, 0}};
  EXPECT_EQ(RangeImage(bad, kEye).along({0, 0, 0}, 3.0), RayEvidence::kUnknown);
  const RangeImage no_eye(wall(), Eigen::Vector3d(std::nan(""), 0, 0));
  EXPECT_EQ(no_eye.along({0, 0, 0}, 3.0), RayEvidence::kUnknown);
}

// The sphere of figure 5.18 where it is, and moved to the empty table in front of the objects:
// the first covers its visible surface and hides nothing the sensor saw; the second claims
// surface exactly where the sensor saw the table.
TEST(SurfaceCoverage, SeenThroughSeparatesAPartFromFreeSpace) {
  const test::Scene s = test::fig_5_18_scene(0.0, 1, 0.6);
  const std::vector<Eigen::Vector3d>& pts = s.rendered.cloud.points;
  const KdTree tree(pts);
  const RangeImage img(pts, s.eye);
  CoverageOptions o;
  o.viewpoint = s.eye;
  o.first_returns = &img;
  const Superquadric ball = test::sphere_model();
  const Eigen::Isometry3d here = s.parts[2].T_world_part;
  Eigen::Isometry3d floating = here;
  floating.translation() = Eigen::Vector3d(40, 0, 80);  // above the empty front of the table
  const SurfaceCoverage at = surface_coverage(ball, here, pts, tree, o);
  const SurfaceCoverage away = surface_coverage(ball, floating, pts, tree, o);
  EXPECT_GT(at.covered, 0.9);
  EXPECT_LT(at.seen_through, 0.02);
  EXPECT_LT(away.covered, 0.1);
  EXPECT_GT(away.seen_through, 0.8);
  o.first_returns = nullptr;  // without the image nothing is counted as seen through
  EXPECT_EQ(surface_coverage(ball, floating, pts, tree, o).seen_through, 0.0);
}

}  // namespace
}  // namespace rangefit
