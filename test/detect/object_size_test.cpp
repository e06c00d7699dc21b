// The size the points of a posed part want (object_hypotheses.hpp size_evidence) on laser-stripe
// scans at about 0.5 mm noise: the true part must read its own size, so that it is confirmed
// while a box a few per cent larger is not. Varied tuning scenes (sim/varied_scene.hpp) whose
// true box, cylinder or cone the size check used to reject, and scenes of a box and a larger one
// with the camera on either side at two triangulation angles.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "detect/object/object_detector.hpp"
#include "sim/varied_scene.hpp"
#include "test/detect/object_scenes.hpp"
#include "test/detect/stripe_scan_fixture.hpp"
#include "test/detect/varied_target.hpp"

namespace rangefit {
namespace object_size_test {

using test::kStripeGeometries;
using test::StripeGeometry;

sim::ScenePart standing(const std::string& name, const Superquadric& sq, double x, double y) {
  return test::placed(name, sq, {x, y, sq.a3}, Eigen::Vector3d::UnitZ());
}

sim::VariedScene scan(std::vector<sim::ScenePart> parts, std::vector<int> target,
                      const StripeGeometry& g, std::uint64_t seed) {
  return test::stripe_scan(std::move(parts), std::move(target),
                           test::single("box", test::box_model()), g, seed, 0.5,
                           test::table_cover());
}

std::string describe(const ObjectDetectResult& r, const StripeGeometry& g) {
  std::string out = std::to_string(g.triangulation_deg) + " deg, side " + std::to_string(g.side) +
                    ": " + to_string(r.reason);
  for (const DetectedInstance& i : r.instances) {
    out += "; found at x " + std::to_string(i.parts[0].center().x()) + " size " +
           std::to_string(i.parts[0].scores.size_scale);
  }
  for (const Rejection& x : r.rejections) {
    out += std::string("; ") + to_string(x.check) + " " + std::to_string(x.value) + " at x " +
           std::to_string(x.centre.x());
  }
  return out;
}

ObjectDetectResult detect(const sim::VariedScene& s, std::uint64_t seed) {
  return test::detect_in(s, seed);
}

// A box 7 % larger all over.
const Superquadric kLarger{26.75, 26.75, 53.5, 0.1, 0.1, 0, 0};

bool found_target(sim::VariedTarget target, std::uint64_t seed, std::string* why) {
  sim::VariedSceneOptions so;
  so.target = target;
  const sim::VariedScene s = sim::make_varied_scene(so, seed);
  const ObjectDetectResult r = detect(s, seed);
  *why = describe(r, {s.factors.scan.triangulation_deg, s.factors.scan.camera_side});
  return r.found() && test::true_positive(r.instances[0].parts[0].T_world_part,
                                          s.parts[static_cast<std::size_t>(s.target_parts[0])],
                                          target != sim::VariedTarget::kSphere);
}

// At ~0.5 mm noise the true box wanted 3-4 % more than its size (G - 1 weighs its narrow faces
// and rounded edges), as much as a look-alike 7 % larger, and was rejected: beside a box 7 %
// larger (seeds 15, 21), under an overhang (21) and behind a wall (29), at 41-49 deg.
TEST(ObjectSize, FindsTheBoxOfVariedScenesAtHalfAMillimetreNoise) {
  for (std::uint64_t seed : {15u, 21u, 29u}) {
    std::string why;
    EXPECT_TRUE(found_target(sim::VariedTarget::kBox, seed, &why)) << "seed " << seed << ": " << why;
  }
}

// The cylinder 42 % hidden by an overhang with the camera on the other side (-y, 26 deg), and
// cones at 18-49 deg, 17-54 % hidden.
TEST(ObjectSize, FindsTheOccludedCylinderAndConesOfVariedScenes) {
  std::string why;
  EXPECT_TRUE(found_target(sim::VariedTarget::kCylinder, 10, &why)) << why;
  for (std::uint64_t seed : {21u, 27u, 28u}) {
    EXPECT_TRUE(found_target(sim::VariedTarget::kCone, seed, &why)) << "seed " << seed << ": " << why;
  }
}

// Cones under overhangs or behind a wall seen by the pan-tilt head at 0.55-0.93 mm noise
// (pan-tilt tuning seeds 146, 179, 187): their points, the lower flank only, want a cone a few per
// cent thinner and taller (3.3-4.8 % off, standard errors 0.3-0.5 %). A scale is off only beyond
// the size tolerance plus three of its standard errors (size_deviation_sigmas).
TEST(ObjectSize, FindsPanTiltConesWhosePointsLeaveTheirSizeLooselyPlaced) {
  for (std::uint64_t seed : {146u, 179u, 187u}) {
    test::expect_varied_target_found(sim::VariedTarget::kCone, seed, true);
  }
}

// Beside a box 7 % larger, the box reads its own size to 2 %.
TEST(ObjectSize, TheBoxReadsItsOwnSizeBesideABoxSevenPercentLarger) {
  for (const StripeGeometry& g : kStripeGeometries) {
    const sim::VariedScene s = scan({standing("box", test::box_model(), -60, 40),
                                     standing("larger box", kLarger, 60, -40)},
                                    {0}, g, 31);
    const ObjectDetectResult r = detect(s, 31);
    ASSERT_TRUE(r.found()) << describe(r, g);
    EXPECT_TRUE(test::true_positive(r.instances[0].parts[0].T_world_part, s.parts[0]))
        << describe(r, g);
    EXPECT_NEAR(r.instances[0].parts[0].scores.size_scale, 1.0, 0.02) << describe(r, g);
  }
}

TEST(ObjectSize, ABoxSevenPercentLargerAloneIsNotTheBox) {
  for (const StripeGeometry& g : kStripeGeometries) {
    const sim::VariedScene s = scan({standing("larger box", kLarger, 0, 0)}, {}, g, 32);
    const ObjectDetectResult r = detect(s, 32);
    EXPECT_FALSE(r.found()) << describe(r, g);
  }
}

TEST(ObjectSize, AnEmptyTableHasNoBox) {
  const sim::VariedScene s = scan({}, {}, kStripeGeometries[0], 33);
  EXPECT_FALSE(detect(s, 33).found());
}

// Varied tuning scenes whose look-alike box, 5-13 % thinner or longer than the model, was taken
// for it at 0.2-0.8 mm noise: the sizes the points want were within the 3 % allowed by the pose
// refitted at three sizes, and the free-size fit reads them. With the box there (seeds 64, 166,
// 216) the box is found; in object-free scenes among such look-alikes (seeds 92, 99, 119)
// nothing is, nor a ball beside a spheroid 4 % taller (seed 51: the model a ball, its scales
// asked along the table's normal).
TEST(ObjectSize, TellsTheBoxFromLookAlikesAFewPerCentThinnerOrLonger) {
  for (std::uint64_t seed : {64u, 166u, 216u}) {
    std::string why;
    EXPECT_TRUE(found_target(sim::VariedTarget::kBox, seed, &why))
        << "seed " << seed << ": " << why;
  }
  for (std::uint64_t seed : {92u, 99u, 119u, 51u}) {
    const sim::VariedScene s = test::object_free_scene(seed);
    const ObjectDetectResult r = detect(s, seed);
    EXPECT_FALSE(r.found()) << "seed " << seed << ": "
                            << describe(r, {s.factors.scan.triangulation_deg,
                                            s.factors.scan.camera_side});
  }
}

// A ball look-alike 5.8 % flatter along a level axis (pan-tilt object-free seeds 79 and 172, the
// model a ball): its scales asked about the table's normal both mix the short axis with the
// others and read 0.977 and 1.028, within the 3 %. Fitted from level axes too, one turns onto it
// and reads 0.943. The true ball beside look-alikes 4.9-18.6 % off (pan-tilt tuning seeds 2-4) is
// still found.
TEST(ObjectSize, ABallFlatterAlongALevelAxisIsNotTheBall) {
  for (std::uint64_t seed : {79u, 172u}) {
    const sim::VariedScene s = test::object_free_scene(seed, true);
    ASSERT_TRUE(s.model.parts[0].shape.ball()) << "seed " << seed;
    const ObjectDetectResult r = detect(s, seed);
    EXPECT_FALSE(r.found()) << "seed " << seed << ": " << test::describe_rejections(r);
  }
  for (std::uint64_t seed : {2u, 3u, 4u}) {
    test::expect_varied_target_found(sim::VariedTarget::kSphere, seed, true);
  }
}

}  // namespace object_size_test
}  // namespace rangefit
