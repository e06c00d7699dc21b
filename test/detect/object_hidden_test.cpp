// A single part mostly hidden (under an overhang) is judged on a smaller measurable share when
// the scan covers all the sensor could have measured of it (ObjectDetectOptions::
// min_measurable_share_covered): varied tuning scenes (sim/varied_scene.hpp) whose true cones
// and box were placed to the millimetre and then rejected as too hidden to judge, at 0.30-0.36
// of their facing surface measurable, all of it covered.
#include <gtest/gtest.h>

#include "test/detect/varied_target.hpp"

namespace rangefit {
namespace object_hidden_test {

using test::expect_varied_target_found;

// Cones under overhangs: 45 deg with the camera at -y (seed 74), 49 deg at +y (180).
TEST(ObjectHidden, FindsConesUnderOverhangsOfVariedScenes) {
  for (std::uint64_t seed : {74u, 180u}) {
    expect_varied_target_found(sim::VariedTarget::kCone, seed);
  }
}

// The box behind a wall that hides half of it (52 %, 45 deg, camera +y, 0.18 mm noise, stripe
// tuning seed 160): two of the first four hypotheses placed it 9 mm along the wall, where it
// passed every check with 0.88 of its measurable surface covered. A search ended by those two took
// the wrong place; a leader not fully covered waits for a third agreeing hypothesis
// (ObjectDetectOptions::confirmations_covered), and the search goes on to the box.
TEST(ObjectHidden, ABoxLeftFreeAlongAWallIsNotTakenOnTwoHypotheses) {
  expect_varied_target_found(sim::VariedTarget::kBox, 160);
}

// A box under an overhang, 0.36 of it measurable.
TEST(ObjectHidden, FindsABoxUnderAnOverhangOfAVariedScene) {
  expect_varied_target_found(sim::VariedTarget::kBox, 158);
}

// The box lying by a wall that hides part of its flank from the camera (14 % hidden, 38 deg, camera
// +y, 0.79 mm noise): placed to the millimetre, it was rejected because 3 of the 11 samples by
// one end lay at the edge of the wall's shadow, measurable by a hair's breadth and bare (open
// end 0.33 against 0.3). Samples next to a hidden one are no evidence of an open end.
TEST(ObjectHidden, FindsTheBoxWhoseEndLiesAtTheEdgeOfAWallsShadow) {
  expect_varied_target_found(sim::VariedTarget::kBox, 183);
}

// The box lying by a wall (11 % hidden, 34 deg, camera +y, 1.74 mm step, 0.63 mm noise): its
// one hypothesis on it came out turned ~10 deg about the table's normal, 3 mm off, and was
// rejected for an open end (0.44 against 0.3) until a near-miss open end was judged again at the
// pose fitted to the points' distances (polish_pose).
TEST(ObjectHidden, FindsTheBoxWhoseYawTheFitLeftOffByAWall) {
  expect_varied_target_found(sim::VariedTarget::kBox, 94);
}

// Spheres by a wall on the camera's side whose faces the vertical laser grazed: the scan holds
// only the wall's top, and the sphere's flank behind the wall counted as measurable and bare
// (coverage 0.54-0.59 against 0.6) until the camera's lines of sight through the laser's shadow
// were taken as unknown (detect/common/laser_shadow.hpp). Tuning seeds 269 (camera +y), 309 and
// 417 (camera -y).
TEST(ObjectHidden, FindsSpheresBehindAWallTheLaserGrazed) {
  for (std::uint64_t seed : {269u, 309u, 417u}) {
    expect_varied_target_found(sim::VariedTarget::kSphere, seed);
  }
}

// Cones under overhangs seen by the pan-tilt head's camera from low beside it (pan-tilt tuning
// seeds 88 and 203, camera -y): its lines of sight to their flanks cross the overhang's laser
// shadow, where nothing is known to be clear. Both were missed when a sample seen only across that
// shadow counted as hidden (one such cone had not one measurable sample with 1,641 scan points on
// it). A scan point at a sample says the camera saw it there.
TEST(ObjectHidden, FindsPanTiltConesUnderOverhangsSeenAcrossTheirLaserShadow) {
  for (std::uint64_t seed : {88u, 203u}) {
    expect_varied_target_found(sim::VariedTarget::kCone, seed, true);
  }
}

// Boxes seen from high above by the pan-tilt head, their flanks grazed (pan-tilt tuning seeds
// 301-600): one standing under an overhang that hides most of its top (30 deg, camera +y, 0.75 mm
// noise, seed 486), one lying behind a wall (49 deg, camera -y, 1.97 mm step, seed 600). Placed to
// the millimetre, each showed 6-7 judgeable samples, short of the 10 needed, and was rejected as
// too hidden; a flank it grazes held some 30 samples more, each with a scan point on it.
TEST(ObjectHidden, FindsPanTiltBoxesByTheFlanksTheyGraze) {
  for (std::uint64_t seed : {486u, 600u}) {
    expect_varied_target_found(sim::VariedTarget::kBox, seed, true);
  }
}

// A box lying behind a wall the pan-tilt head's sweep stopped short of (pan-tilt tuning seed
// 313: 15 % hidden, 24 deg, camera -y, 0.20 mm noise): the laser never lit the wall, so the scan
// holds not one point of it, but it stood on the camera's lines of sight to one end of the box.
// Placed to the millimetre, the box was rejected for that end (open end 0.40 against 0.3) until
// a line of sight through space no laser plane of the sweep held was taken as unknown.
TEST(ObjectHidden, FindsABoxBehindAWallTheSweepStoppedShortOf) {
  expect_varied_target_found(sim::VariedTarget::kBox, 313, true);
}

// The laser's shadow hides nothing of what tells a look-alike apart: a box 9 % shorter (tuning
// seed 139, the true box elsewhere in the scene; object-free seed 174 with the box model) keeps the
// bare strip the posed box claims past its end, where lone outliers in the air had cast shadow
// columns over the camera's lines of sight and the look-alike was confirmed.
TEST(ObjectHidden, TheLaserShadowLeavesAShorterLookAlikesEndBare) {
  expect_varied_target_found(sim::VariedTarget::kBox, 139);
  sim::VariedSceneOptions so;
  so.target = sim::VariedTarget::kNone;
  sim::VariedScene s = sim::make_varied_scene(so, 174);
  s.model = test::single("box", test::box_model());
  EXPECT_FALSE(test::detect_in(s, 174).found());
}

// What is not all there stays rejected: the object-free varied scenes have no cone or box.
TEST(ObjectHidden, ObjectFreeVariedScenesHaveNoConeOrBox) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    sim::VariedSceneOptions so;
    so.target = sim::VariedTarget::kNone;
    sim::VariedScene s = sim::make_varied_scene(so, seed);
    for (const ObjectModel& m : {test::single("cone", test::cone_model()),
                                 test::single("box", test::box_model())}) {
      s.model = m;
      EXPECT_FALSE(test::detect_in(s, seed).found()) << "seed " << seed << " " << m.parts[0].name;
    }
  }
}

}  // namespace object_hidden_test
}  // namespace rangefit
