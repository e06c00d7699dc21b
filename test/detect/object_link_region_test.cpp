// Where a compound model's link puts a part given its sibling (object_link_region.hpp): the
// mallet's shaft in its head's middle plane, pointing at it; its head on the shaft's line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numbers>
#include <vector>

#include "detect/common/kdtree.hpp"
#include "detect/object/object_link_region.hpp"
#include "sim/scene_objects.hpp"

namespace rangefit {
namespace {

// A head lying at the origin with its axis along y; its shaft along x, its centre 170 mm out in
// the head's middle plane (the model's link: 90 deg, 170 mm, bearings 90 and 0 deg).
Eigen::Isometry3d head_pose() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY())
          .toRotationMatrix();
  return T;
}

Eigen::Isometry3d shaft_pose() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX())
          .toRotationMatrix();
  T.translation() = Eigen::Vector3d(170.0, 0.0, 0.0);
  return T;
}

// Labelled probe points: on the true shaft, on the true head, and elsewhere.
struct Probes {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::uint32_t> shaft, head, beside_head, across;
};

Probes probes() {
  Probes p;
  const auto add = [&](std::vector<std::uint32_t>& label, const Eigen::Vector3d& x) {
    label.push_back(static_cast<std::uint32_t>(p.points.size()));
    p.points.push_back(x);
  };
  for (double x = 60.0; x <= 290.0; x += 10.0) add(p.shaft, {x, 0.0, 12.0});  // its top line
  for (double y = -50.0; y <= 50.0; y += 10.0) add(p.head, {0.0, y, 30.0});   // the head's top
  // A rod beside the head, parallel to the shaft's line but 80 mm off the middle plane, and one
  // lying across the shaft's line at the link's distance.
  for (double x = 60.0; x <= 250.0; x += 10.0) add(p.beside_head, {x, 80.0, 12.0});
  for (double y = 40.0; y <= 120.0; y += 10.0) add(p.across, {170.0, y, 12.0});
  return p;
}

// How many of the points `which` the region (ascending indices) holds.
std::size_t held(const std::vector<std::uint32_t>& region,
                 const std::vector<std::uint32_t>& which) {
  return static_cast<std::size_t>(std::count_if(which.begin(), which.end(), [&](std::uint32_t i) {
    return std::binary_search(region.begin(), region.end(), i);
  }));
}

TEST(LinkRegion, TheShaftLiesInItsHeadsMiddlePlanePointingAtIt) {
  const ObjectModel m = sim::mallet_model();
  const Probes p = probes();
  const KdTree tree(p.points);
  // The shaft given its head: the link's first part is the head.
  const std::vector<std::uint32_t> r =
      link_region(m.links[0], false, m.parts[1].shape, head_pose(), 5.0, p.points, tree);
  ASSERT_TRUE(std::is_sorted(r.begin(), r.end()));
  EXPECT_EQ(held(r, p.shaft), p.shaft.size());
  EXPECT_EQ(held(r, p.beside_head), 0u);
  EXPECT_EQ(held(r, p.across), 0u);
}

TEST(LinkRegion, TheHeadLiesOnItsShaftsLine) {
  const ObjectModel m = sim::mallet_model();
  const Probes p = probes();
  const KdTree tree(p.points);
  const std::vector<std::uint32_t> r =
      link_region(m.links[0], true, m.parts[0].shape, shaft_pose(), 5.0, p.points, tree);
  EXPECT_EQ(held(r, p.head), p.head.size());
  // Around the shaft's far end as well (the link does not say which end the head is on), not
  // along the middle of the shaft.
  EXPECT_TRUE(std::binary_search(r.begin(), r.end(), p.shaft.back()));
  const std::uint32_t middle = p.shaft[p.shaft.size() / 2];
  EXPECT_FALSE(std::binary_search(r.begin(), r.end(), middle));
}

TEST(LinkRegion, WithoutBearingsAShellAroundTheSibling) {
  ObjectModel m = sim::mallet_model();
  m.links[0].bearing_rad.reset();
  const Probes p = probes();
  const KdTree tree(p.points);
  const std::vector<std::uint32_t> r =
      link_region(m.links[0], false, m.parts[1].shape, head_pose(), 5.0, p.points, tree);
  // Everything within the shaft's reach of the 170 mm sphere: the rod beside the head too.
  EXPECT_EQ(held(r, p.shaft), p.shaft.size());
  EXPECT_EQ(held(r, p.beside_head), p.beside_head.size());
}

}  // namespace
}  // namespace rangefit
