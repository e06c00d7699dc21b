// The rims of a single part's flat caps (object_coverage.hpp open_rim, ObjectDetectOptions::
// max_open_rim): a standing box or can seen from above whose points leave its size open is fitted
// by one corner or flank to a look-alike a tenth narrower as well as to itself; the model's top
// face then reaches past the look-alike's edge, where the scan shows the table instead. Varied
// tuning scenes (sim/varied_scene.hpp) where a narrower standing look-alike was taken for the
// target, and a narrower box alone with the camera on either side at two triangulation angles.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "detect/object/object_detector.hpp"
#include "sim/varied_scene.hpp"
#include "test/detect/object_scenes.hpp"
#include "test/detect/stripe_scan_fixture.hpp"
#include "test/detect/varied_target.hpp"

namespace rangefit {
namespace object_rim_test {

using test::kStripeGeometries;
using test::StripeGeometry;

std::string describe(const ObjectDetectResult& r) {
  std::string out = to_string(r.reason);
  for (const DetectedInstance& i : r.instances) {
    const PartScores& s = i.parts[0].scores;
    out += "; found at " + std::to_string(i.parts[0].center().x()) + " " +
           std::to_string(i.parts[0].center().y()) + " rim " + std::to_string(s.open_rim) +
           " size " + (s.size_determined ? std::to_string(s.size_scale) : "open");
  }
  return out;
}

bool true_target(sim::VariedTarget target, std::uint64_t seed, std::string* why) {
  sim::VariedSceneOptions so;
  so.target = target;
  const sim::VariedScene s = sim::make_varied_scene(so, seed);
  const ObjectDetectResult r = test::detect_in(s, seed);
  *why = describe(r);
  return r.found() && test::true_positive(r.instances[0].parts[0].T_world_part,
                                          s.parts[static_cast<std::size_t>(s.target_parts[0])]);
}

// A box 13 % narrower standing beside the lying target (seed 110, 22 deg, +y), 9 % narrower
// under an overhang (127, 0.1 mm noise) and 10 % narrower at 0.9 mm noise (148): each was
// confirmed as the box, its size left open by its points.
TEST(ObjectRim, TheBoxOfVariedScenesIsNotANarrowerStandingBox) {
  for (std::uint64_t seed : {110u, 127u, 148u}) {
    std::string why;
    EXPECT_TRUE(true_target(sim::VariedTarget::kBox, seed, &why)) << "seed " << seed << ": " << why;
  }
}

// The same with narrower standing cans beside the cylinder, at 0.5-0.9 mm noise.
TEST(ObjectRim, TheCylinderOfVariedScenesIsNotANarrowerStandingCan) {
  for (std::uint64_t seed : {100u, 122u, 124u}) {
    std::string why;
    EXPECT_TRUE(true_target(sim::VariedTarget::kCylinder, seed, &why))
        << "seed " << seed << ": " << why;
  }
}

// Object-free varied tuning scenes with a standing box as tall as the model and narrower: 6 %
// (seed 168, 41 deg, +y), the size fit reading 1.01 (its one scale across the axis is tied by the
// height), and 18 % (seed 195, 36 deg, -y), the model's top overhanging it by 9 mm, beyond the
// first scale's strip (the scenes search for the box). Both were taken for the box while the rim
// was judged only where the size was open, at one scale.
TEST(ObjectRim, ObjectFreeScenesWithNarrowerStandingBoxesHaveNoBox) {
  for (std::uint64_t seed : {168u, 195u}) {
    const sim::VariedScene s = test::object_free_scene(seed);  // the model drawn: the box
    ASSERT_EQ(s.model.parts[0].shape.a3, test::box_model().a3) << "seed " << seed;
    const ObjectDetectResult r = test::detect_in(s, seed);
    EXPECT_FALSE(r.found()) << "seed " << seed << ": " << describe(r);
  }
}

sim::VariedScene standing_alone(const Superquadric& sq, const StripeGeometry& g,
                                std::uint64_t seed) {
  return test::stripe_scan({test::placed("box", sq, {0, 0, sq.a3}, Eigen::Vector3d::UnitZ())},
                           {0}, test::single("box", test::box_model()), g, seed, 0.5,
                           test::table_cover());
}

// A standing box 12 % narrower (and as tall) alone on the table is not the box; the box itself,
// standing alone, is found with its cap's rims shown.
TEST(ObjectRim, ANarrowerStandingBoxAloneIsNotTheBox) {
  const Superquadric narrower{22.0, 22.0, 50.0, 0.1, 0.1, 0, 0};
  for (const StripeGeometry& g : kStripeGeometries) {
    const std::string at = std::to_string(g.triangulation_deg) + " deg, side " +
                           std::to_string(g.side) + ": ";
    const ObjectDetectResult wrong = test::detect_in(standing_alone(narrower, g, 41), 41);
    EXPECT_FALSE(wrong.found()) << at << describe(wrong);
    const sim::VariedScene s = standing_alone(test::box_model(), g, 42);
    const ObjectDetectResult right = test::detect_in(s, 42);
    ASSERT_TRUE(right.found()) << at << describe(right);
    EXPECT_TRUE(test::true_positive(right.instances[0].parts[0].T_world_part, s.parts[0]))
        << at << describe(right);
    EXPECT_LE(right.instances[0].parts[0].scores.open_rim, 0.15) << at << describe(right);
  }
}

}  // namespace object_rim_test
}  // namespace rangefit
