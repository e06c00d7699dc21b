// The compound mallet (head + shaft, thesis 5.1.3) where its flat ends show no points: a head
// lying with its caps along the sweep, a shaft whose ends are hidden. The pose fit leaves such a
// part free along its axis; the scan's wall points and the link place it
// (detect/object/object_axial_slide.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "detect/common/kdtree.hpp"
#include "detect/object/object_axial_slide.hpp"
#include "detect/object/object_detector.hpp"
#include "sim/varied_scene.hpp"
#include "test/detect/object_scenes.hpp"

namespace rangefit {
namespace object_mallet_test {

// The upper half of a lying can's side wall from z0 to z1 (part frame: axis z, radius 30), as a
// scan sees it with its caps grazed: no points on them.
std::vector<Eigen::Vector3d> wall(double z0, double z1) {
  std::vector<Eigen::Vector3d> pts;
  for (double z = z0; z <= z1; z += 1.0) {
    for (double phi = 0.0; phi <= std::numbers::pi; phi += 0.05) {
      pts.emplace_back(30.0 * std::cos(phi), 30.0 * std::sin(phi), z);
    }
  }
  return pts;
}

Eigen::Isometry3d at_z(double z) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation().z() = z;
  return T;
}

const Superquadric kCan{30, 30, 50, 0.1, 1, 0, 0};

// Posed 4 mm short of where its wall ends, the can is slid back onto its wall.
TEST(AxialSlide, MovesAPartToWhereItsWallEnds) {
  const std::vector<Eigen::Vector3d> pts = wall(-50.0, 50.0);
  const KdTree tree(pts);
  for (double off : {-4.0, 4.0, 9.0}) {
    const Eigen::Isometry3d T = slide_to_wall(kCan, at_z(off), pts, tree);
    EXPECT_NEAR(T.translation().z(), 0.0, 0.5) << "posed " << off << " mm off";
    EXPECT_NEAR(T.translation().x(), 0.0, 1e-9);
  }
}

// A wall longer than the part (a longer look-alike) is not explained away by sliding: that is
// the continuation check's evidence. A wall hidden at both ends leaves the part where it was,
// or where other evidence prefers within what the wall allows.
TEST(AxialSlide, LeavesLongerAndHiddenWallsAlone) {
  const std::vector<Eigen::Vector3d> longer = wall(-60.0, 60.0), hidden = wall(-30.0, 30.0);
  const KdTree longer_tree(longer), hidden_tree(hidden);
  EXPECT_NEAR(slide_to_wall(kCan, at_z(10.0), longer, longer_tree).translation().z(), 10.0, 1e-9);
  EXPECT_NEAR(slide_to_wall(kCan, at_z(5.0), hidden, hidden_tree).translation().z(), 5.0, 1e-9);
  AxialSlideOptions o;
  o.prefer = Eigen::Vector3d(0.0, 0.0, 12.0);  // within the 20 mm the hidden wall leaves free
  EXPECT_NEAR(slide_to_wall(kCan, at_z(5.0), hidden, hidden_tree, o).translation().z(), 17.0, 1e-9);
  o.prefer.z() = 40.0;  // beyond: as far as the wall allows (its end at the cap, z = -30)
  EXPECT_NEAR(slide_to_wall(kCan, at_z(5.0), hidden, hidden_tree, o).translation().z(), 20.0, 0.5);
}

// The wall's points gathered once at a pose answer every preference as the whole slide does: a
// part slid several ways from one pose (a rejected candidate's rescue) gathers them once.
TEST(AxialSlide, TheWallGatheredOnceAnswersEveryPreference) {
  const std::vector<Eigen::Vector3d> hidden = wall(-30.0, 30.0);
  const KdTree tree(hidden);
  const WallRuns runs = wall_runs(kCan, at_z(5.0), hidden, tree);
  EXPECT_FALSE(runs.along[2].empty());
  EXPECT_TRUE(runs.along[0].empty());  // a round section is not slid across
  for (double prefer : {0.0, 12.0, -12.0, 40.0}) {
    AxialSlideOptions o;
    o.prefer.z() = prefer;
    const Eigen::Isometry3d whole = slide_to_wall(kCan, at_z(5.0), hidden, tree, o);
    EXPECT_TRUE(slide_to_wall(kCan, runs, o).isApprox(whole, 1e-12)) << "prefer " << prefer;
  }
  AxialSlideOptions o;
  o.prefer.z() = -12.0;  // within the 20 mm the hidden wall leaves free, the other way
  EXPECT_NEAR(slide_to_wall(kCan, runs, o).translation().z(), -7.0, 1e-9);
}

// A few stray points on the wall's line within the part's length but apart from its run (another
// object's, a shadow's edge) do not stand for the wall: the part, posed 19 mm past its wall's end
// with its other end hidden, is slid onto the run, as far as `prefer` asks and the run allows.
TEST(AxialSlide, SlidesOntoTheWallsRunNotOntoStrayPoints) {
  std::vector<Eigen::Vector3d> pts = wall(-31.0, 80.0);  // the can at z = 19, its far end hidden
  for (double z = -48.0; z <= -44.0; z += 1.0) pts.emplace_back(0.0, 30.0, z);
  const KdTree tree(pts);
  AxialSlideOptions o;
  o.prefer = Eigen::Vector3d(0.0, 0.0, 50.0);
  EXPECT_NEAR(slide_to_wall(kCan, at_z(0.0), pts, tree, o).translation().z(), 19.0, 0.5);
}

// Another surface crossing the plane of the wall past the part's end (a lower neighbour's top
// meeting a lying box's flank) leaves a line of points on the wall's extension. It is not the
// wall: along its axis a wall reaches around it. The can posed 12 mm past its wall's end is slid
// back, not taken for a longer look-alike's wall.
TEST(AxialSlide, ALineCrossingTheWallsPlanePastItsEndDoesNotCarryItOn) {
  std::vector<Eigen::Vector3d> pts = wall(-50.0, 50.0);
  for (double z = 53.0; z <= 72.0; z += 1.0) {  // from 3 mm past the end
    pts.emplace_back(30.0 * std::cos(0.5), 30.0 * std::sin(0.5), z);
  }
  const KdTree tree(pts);
  EXPECT_NEAR(slide_to_wall(kCan, at_z(12.0), pts, tree).translation().z(), 0.0, 0.5);
}

// A neighbour's face 10 mm past a long part's end (a box beside a shaft's far cap) crosses the
// wall's extension all around the axis. A gap of 10 mm along a shaft 240 mm long still ends the
// wall's run: the shaft posed 7.5 mm towards the face is slid back onto its own wall.
TEST(AxialSlide, ANeighboursFaceAGapPastALongPartsEndDoesNotCarryItOn) {
  const Superquadric rod{12, 12, 120, 0.1, 1, 0, 0};
  std::vector<Eigen::Vector3d> pts;
  for (double z = -120.0; z <= 130.0; z += 1.0) {
    if (z > 120.0 && z < 130.0) continue;  // the gap; from 130 mm on, the neighbour's face
    for (double phi = 0.0; phi <= std::numbers::pi; phi += 0.1) {
      pts.emplace_back(12.0 * std::cos(phi), 12.0 * std::sin(phi), z);
    }
  }
  const KdTree tree(pts);
  EXPECT_NEAR(slide_to_wall(rod, at_z(7.5), pts, tree).translation().z(), 0.0, 0.5);
}

// Varied stripe scenes (tuning seeds; sim/varied_scene.hpp) where the detector placed the mallet
// wrongly: seed 7, a head lying with its caps along the sweep, fitted 4 mm short of its wall's
// end and rejected as continuing past it; seed 28, its shaft 3-4 mm off along its axis; seed 15,
// a shaft rolled about its axis. Both parts must be the true ones (centre < 3 mm, axis < 5 deg).
void expect_mallet_found(std::uint64_t seed, bool two_cameras = false, bool pan_tilt = false) {
  sim::VariedSceneOptions so;
  so.target = sim::VariedTarget::kMallet;
  so.two_camera_probability = two_cameras ? 1.0 : 0.0;
  so.pan_tilt = pan_tilt;
  const sim::VariedScene s = sim::make_varied_scene(so, seed);
  ObjectDetectOptions o;
  o.seed = seed;
  o.sensor = s.view;
  const ObjectDetectResult r = detect_object(s.model, s.cloud.points, o);
  ASSERT_TRUE(r.found()) << "seed " << seed << ": " << to_string(r.reason);
  for (std::size_t p = 0; p < s.target_parts.size(); ++p) {
    const sim::ScenePart& truth = s.parts[static_cast<std::size_t>(s.target_parts[p])];
    const test::PoseError e = test::pose_error(r.instances[0].parts[p].T_world_part, truth);
    EXPECT_TRUE(test::true_positive(r.instances[0].parts[p].T_world_part, truth))
        << "seed " << seed << ", " << truth.name << ": " << e.centre_mm << " mm off";
  }
}

TEST(ObjectMallet, PlacedAlongItsAxesWhereItsEndsShowNoPoints) {
  for (std::uint64_t seed : {7u, 15u, 28u}) expect_mallet_found(seed);
}

// Varied stripe scenes (tuning seeds) where one part was partly hidden and shows less than
// min_coverage of what the sensor could have measured of it, the other part fully seen: seed 14,
// the head under an overhang (0.53); seed 16, the shaft behind a wall (0.50). The object is
// judged by the coverage of both parts together.
TEST(ObjectMallet, FoundWithOnePartPartlyHidden) {
  for (std::uint64_t seed : {14u, 16u}) expect_mallet_found(seed);
}

// Varied stripe scenes (tuning seeds) where angle and distance alone (eq. 5.5-5.6) linked the
// wrong parts: seed 34, the true shaft with the true head placed 37 mm along its own axis (the
// shaft's centre no longer in the head's middle plane); seed 207, a standing drum of the head's
// size beside the true shaft; seed 330, the true head with a look-alike's shaft that lies in line
// with the true one at the link's distance. The link's bearings (PartLink::bearing_rad) rank and
// gate them out and slide the head to where the shaft's line crosses it.
TEST(ObjectMallet, PartsSitWhereTheLinksBearingsPutThem) {
  for (std::uint64_t seed : {34u, 207u, 330u}) expect_mallet_found(seed);
}

// Seed 298: the head's wall shows one cap's end, the other end hidden, and the slide along the
// wall stopped where its run first fits, 7 mm short; it goes on to where the scan shows the end.
TEST(ObjectMallet, FoundWhereItsHeadShowsOnlyOneEnd) { expect_mallet_found(298); }

// Two-camera varied scenes (tuning seeds) in which every hypothesis of the head over the whole
// scan went elsewhere: seeds 301 and 570, a wall in front of the mallet whose flat patches a
// lying can fits better than the head's own noisy ones; seed 585, a look-alike head 20 % larger.
// The found shaft says where the head must be, and hypotheses seeded there find it
// (object_link_region.hpp).
TEST(ObjectMallet, AHeadMissedOverTheWholeScanIsFoundWhereItsShaftPutsIt) {
  for (std::uint64_t seed : {301u, 570u, 585u}) expect_mallet_found(seed, true);
}

// Two-camera seed 377: a clutter box stands 11 mm past the shaft's far cap; its face carried the
// shaft's wall run on, and the shaft stayed 7.5 mm off along its axis, away from the head.
TEST(ObjectMallet, AShaftIsNotHeldOffItsWallByANeighbourPastItsEnd) {
  expect_mallet_found(377, true);
}

// Pan-tilt varied scenes (tuning seeds) with the mallet mostly hidden (0.68-0.82 of a part lost):
// the head's hypotheses were screened at their own poses before the parts were linked, and on
// seed 133 the true head's showed 0.056 of its surface seen through against the confirmation's
// 0.05; on seeds 178 and 181 the vote was left with no linked pair. The screen allows more than
// the confirmation of the linked object does (compound_screen_slack).
TEST(ObjectMallet, AHeadFittedALittleOffIsNotScreenedOutBeforeItIsLinked) {
  for (std::uint64_t seed : {133u, 178u, 181u}) expect_mallet_found(seed, false, true);
}

// Seed 148: a look-alike mallet 10 % smaller, fitted to the model, sinks 6 mm into the table
// with both parts (a true mallet rests on it with its head); it is not taken for the mallet.
TEST(ObjectMallet, ASmallerLookAlikeSunkIntoTheTableIsNotTaken) {
  sim::VariedSceneOptions so;
  so.target = sim::VariedTarget::kMallet;
  const sim::VariedScene s = sim::make_varied_scene(so, 148);
  ObjectDetectOptions o;
  o.seed = 148;
  o.sensor = s.view;
  const ObjectDetectResult r = detect_object(s.model, s.cloud.points, o);
  for (const DetectedInstance& inst : r.instances) {
    for (std::size_t p = 0; p < s.target_parts.size(); ++p) {
      const sim::ScenePart& truth = s.parts[static_cast<std::size_t>(s.target_parts[p])];
      EXPECT_TRUE(test::true_positive(inst.parts[p].T_world_part, truth))
          << truth.name << ": " << test::pose_error(inst.parts[p].T_world_part, truth).centre_mm
          << " mm off";
    }
  }
}

}  // namespace object_mallet_test
}  // namespace rangefit
