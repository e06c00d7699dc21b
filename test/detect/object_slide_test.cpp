// A single part rejected because the scan carries on past one of its flat faces, because one
// of its ends shows no wall, or because the sensor saw through part of it, is slid along its wall
// to where the wall's points end and judged there (object_detector.cpp slide_to_confirm); a
// confirmed one whose wall runs past one end is settled there (settle_along_wall): a lying box or
// can fitted from a patch near one end is left free along its side walls by the pose fit, and every
// hypothesis of the varied tuning scenes below stopped short of one end or reached past it.
#include <gtest/gtest.h>

#include "test/detect/varied_target.hpp"

namespace rangefit {
namespace object_slide_test {

using test::expect_varied_target_found;

// The box lying behind a wall (12 % hidden, 31 deg, camera -y, 0.16 mm noise): the best
// candidate stood 17 mm along its axis, the scan carrying on past its end.
TEST(ObjectSlide, FindsTheLyingBoxOfAVariedSceneSlidAlongItsWall) {
  expect_varied_target_found(sim::VariedTarget::kBox, 181);
}

// The lying cylinder behind a wall (30 % hidden, 23 deg, camera -y, 1 mm noise): 17 mm short.
TEST(ObjectSlide, FindsTheLyingCylinderOfAVariedSceneSlidAlongItsWall) {
  expect_varied_target_found(sim::VariedTarget::kCylinder, 197);
}

// The box lying behind a wall (27 % hidden, 29 deg, camera -y, 0.53 mm noise) whose far end the
// wall hides: every candidate reached 6 mm past the end the scan shows, and its wall there was
// bare (open end 0.5).
TEST(ObjectSlide, FindsTheLyingBoxSlidBackFromTheEndWhoseWallIsBare) {
  expect_varied_target_found(sim::VariedTarget::kBox, 184);
}

// The box lying under an overhang that hides one end (16 % hidden, 33 deg, camera -y, 0.77 mm
// noise): confirmed 6.4 mm into the hidden end, its wall's points running on past the other end
// by as much, within the rounded edge the continuation check does not look at. Its best
// candidate stands 11 mm into the hidden end, rejected because a cap's rim reaches past the face
// the scan shows: slid either way as far as its wall's run allows.
TEST(ObjectSlide, SettlesTheLyingBoxWhereItsWallsPointsEnd) {
  expect_varied_target_found(sim::VariedTarget::kBox, 185);
}

// Tuning seeds 231-430. The box lying beside an overhang's leg (14 % hidden, 19 deg, camera -y,
// 0.95 mm noise): the best candidate stood 14 mm along its axis, its end where the laser saw the
// table (seen through 0.065). The box under an overhang (38 %, 41 deg, 0.82 mm): 10 mm off, seen
// through 0.059. And one under an overhang (40 %, 35 deg, camera +y, 0.80 mm) 20 mm off, whose
// wall's run fits it where it stood: slid as far as the run allows, one way and then the other.
TEST(ObjectSlide, FindsTheLyingBoxSlidBackFromWhereTheSensorSawThrough) {
  for (std::uint64_t seed : {336u, 348u, 415u}) {
    expect_varied_target_found(sim::VariedTarget::kBox, seed);
  }
}

// Tuning seeds 231-430. The box lying behind a wall that hides its near end (11 % hidden, 47
// deg, camera -y, 0.87 mm noise): slid onto its wall, the free size fit read it 5.8 % short
// (sigma 0.4 %), taking the end of the points for the box's end. Shorter along the axis is no
// evidence where an end is hidden.
TEST(ObjectSlide, ALyingBoxWhoseNearEndIsHiddenIsNotJudgedShort) {
  expect_varied_target_found(sim::VariedTarget::kBox, 277);
}

// Tuning seeds 231-430. The box lying under an overhang (28 % hidden, 28 deg, camera -y, 0.49 mm
// noise) end to end with a lying look-alike whose top, 10 mm lower, crosses the plane of the
// box's flank past its end: that line of points carried the wall's run on, longer than the box,
// and the candidate standing 13 mm along its axis (open end 0.68) was not slid. Along its axis a
// wall reaches around it; a line does not.
TEST(ObjectSlide, ALineWhereANeighbourCrossesTheWallsPlaneDoesNotCarryTheWallOn) {
  expect_varied_target_found(sim::VariedTarget::kBox, 419);
}

// Pan-tilt tuning seeds. The box lying behind a wall (33 % hidden, 41 deg, camera +y, 0.56 mm
// noise, seed 29): the best candidate stood 13 mm along its axis past the hidden end, where its
// wall's run fit it as well, and the scan carried on past its other end (0.011 against 0.01).
// The box under an overhang (33 %, 0.69 mm, seed 171): 37 mm along, carrying on 0.107. Slid as
// little as possible they stayed; slid either way as far as the run allows, they came to the box.
TEST(ObjectSlide, FindsAPanTiltLyingBoxFittedPastItsHiddenEnd) {
  for (std::uint64_t seed : {29u, 171u})
    expect_varied_target_found(sim::VariedTarget::kBox, seed, true);
}

// Pan-tilt tuning seed 86. The box standing behind a wall (39 % hidden, 0.01 mm noise), seen on
// part of its top: its best candidate stood 15 mm across, where the laser saw the table past it
// (seen through 0.091 against 0.05). Slid across its flanks as far as their run allows, it came to
// the box.
TEST(ObjectSlide, FindsAPanTiltStandingBoxFittedAcrossItsHalfSeenTop) {
  expect_varied_target_found(sim::VariedTarget::kBox, 86, true);
}

// Pan-tilt tuning seeds. Lying boxes seen from above, their flanks grazed or hidden: under an
// overhang (14 % hidden, 17 deg, 0.51 mm noise, seed 225), behind walls (29 and 30 %, 0.36 and
// 0.99 mm, seeds 195, 197). Their best candidates lay turned about the table's normal by 11, 20
// and 90 deg, where their refinement had settled from a start on the top face, and failed the
// open-end or continuation checks. Turned by an eighth or a quarter and fitted again, they came
// to the box.
TEST(ObjectSlide, FindsAPanTiltLyingBoxFittedTurnedOnItsTopFace) {
  for (std::uint64_t seed : {225u, 195u, 197u})
    expect_varied_target_found(sim::VariedTarget::kBox, seed, true);
}

}  // namespace object_slide_test
}  // namespace rangefit
