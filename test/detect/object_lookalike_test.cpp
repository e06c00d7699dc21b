// Object detection among look-alikes that differ from the model along one axis only, and a
// compound model's parts found on two unrelated objects: laser-stripe scans with the camera on
// either side at two triangulation angles (sim/varied_scene.hpp scan_varied_scene), the sensor
// known. Each scene was taken for the model by the detector before the scan's continuation past
// a part's faces and the links after the joint refinement were checked.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "detect/object/object_continuation.hpp"
#include "detect/object/object_detector.hpp"
#include "sim/scene_objects.hpp"
#include "sim/varied_scene.hpp"
#include "test/detect/object_scenes.hpp"
#include "test/detect/stripe_scan_fixture.hpp"
#include "test/detect/varied_target.hpp"

namespace rangefit {
namespace object_lookalike_test {

using test::StripeGeometry;
// Both camera sides and both triangulation angles in two scans (the suite stays fast; each of
// these scenes failed under all four combinations before).
constexpr StripeGeometry kGeometries[] = {{20.0, +1}, {45.0, -1}};

sim::ScenePart part(const std::string& name, const Superquadric& sq, const Eigen::Vector3d& c,
                    const Eigen::Vector3d& axis) {
  return test::placed(name, sq, c, axis);
}

sim::VariedScene scan(std::vector<sim::ScenePart> parts, std::vector<int> target, ObjectModel model,
                      const StripeGeometry& g, std::uint64_t seed, double noise_mm = 0.1) {
  return test::stripe_scan(std::move(parts), std::move(target), std::move(model), g, seed,
                           noise_mm, test::table_cover(260.0));
}

ObjectDetectResult detect(const sim::VariedScene& s, std::uint64_t seed) {
  return test::detect_in(s, seed);
}

std::string describe(const ObjectDetectResult& r) {
  std::string out = to_string(r.reason);
  for (const DetectedInstance& i : r.instances) {
    for (const DetectedPart& p : i.parts) {
      out += "; found " + p.name + " at " + std::to_string(p.center().x()) + " " +
             std::to_string(p.center().y());
    }
  }
  return out;
}

const Superquadric kLongCan{30, 30, 57.5, 0.1, 1, 0, 0};  // the cylinder 15 % longer
const Superquadric kBlock{35, 25, 20, 0.1, 0.1, 0, 0};

// A can 15 % longer than the cylinder model, lying, scanned with 0.5 mm noise: every part of it
// fits the model, so only the scan going on past the model's cap shows it is not the cylinder.
TEST(ObjectLookAlike, ALongerCanIsNotTakenForTheCylinder) {
  for (const StripeGeometry& g : kGeometries) {
    const sim::VariedScene s =
        scan({part("long can", kLongCan, {0, 0, 30}, Eigen::Vector3d::UnitX()),
              part("block", kBlock, {-60, 150, 20}, Eigen::Vector3d::UnitZ())},
             {}, test::single("cylinder", test::cylinder_model()), g, 11, 0.5);
    const ObjectDetectResult r = detect(s, 11);
    EXPECT_FALSE(r.found()) << g.triangulation_deg << " deg, side " << g.side << ": "
                            << describe(r);
  }
}

// The same can beside the real cylinder, also lying: the cylinder is found, not the can.
TEST(ObjectLookAlike, FindsTheCylinderBesideALongerCan) {
  for (const StripeGeometry& g : kGeometries) {
    const sim::VariedScene s =
        scan({part("cylinder", test::cylinder_model(), {0, 160, 30}, Eigen::Vector3d::UnitX()),
              part("long can", kLongCan, {0, 0, 30}, Eigen::Vector3d::UnitX())},
             {0}, test::single("cylinder", test::cylinder_model()), g, 12);
    const ObjectDetectResult r = detect(s, 12);
    ASSERT_TRUE(r.found()) << g.triangulation_deg << " deg, side " << g.side << ": " << describe(r);
    EXPECT_TRUE(test::true_positive(r.instances[0].parts[0].T_world_part, s.parts[0]))
        << g.triangulation_deg << " deg, side " << g.side << ": " << describe(r);
  }
}

// A head-sized drum and a shaft-sized rod at right angles, the rod's end 45 mm short of the
// drum: each part fits perfectly and the link is 26 mm off, inside the vote's gate; refined
// together they stay apart, so this is no mallet.
TEST(ObjectLookAlike, ADrumAndARodApartAreNotTheMallet) {
  const ObjectModel mallet = sim::mallet_model();
  for (const StripeGeometry& g : kGeometries) {
    const sim::VariedScene s =
        scan({part("drum", mallet.parts[0].shape, {0, 0, 30}, Eigen::Vector3d::UnitX()),
              part("rod", mallet.parts[1].shape, {0, 195, 10}, Eigen::Vector3d::UnitY())},
             {}, mallet, g, 13);
    const ObjectDetectResult r = detect(s, 13);
    EXPECT_FALSE(r.found()) << g.triangulation_deg << " deg, side " << g.side << ": "
                            << describe(r);
  }
}

// The continuation itself, on exact points: the side wall of a can 20 % longer than the model
// carries on past the model's cap when the model sits on one end of it; a can of the model's
// own length does not.
TEST(ObjectLookAlike, ContinuationSeesTheSideWallGoOnPastTheCap) {
  const Superquadric model = test::cylinder_model();  // 30, 30, 50
  const auto side_wall = [](double half_length) {
    std::vector<Eigen::Vector3d> pts;
    for (double z = -half_length; z <= half_length; z += 1.0) {
      for (double phi = 0.0; phi < std::numbers::pi; phi += 0.05) {
        pts.emplace_back(30.0 * std::cos(phi), 30.0 * std::sin(phi), z);
      }
    }
    return pts;
  };
  const std::vector<Eigen::Vector3d> same = side_wall(50.0), longer = side_wall(60.0);
  const KdTree same_tree(same), longer_tree(longer);
  const Eigen::Isometry3d at_centre = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d at_end = Eigen::Isometry3d::Identity();
  at_end.translation().z() = 10.0;  // one cap flush with the longer can's end
  const Continuation own = surface_continuation(model, at_centre, same, same_tree);
  const Continuation past = surface_continuation(model, at_end, longer, longer_tree);
  EXPECT_GT(own.surface, 1000);
  EXPECT_LT(own.share, 0.005);
  EXPECT_GT(past.share, 0.05);  // 20 of 110 mm of wall beyond the cap, less the margins
}

// At 0.8 mm noise (a band of 2.4 mm) the top of a standing box 18 % wider than the model, the
// model posed on one corner of it (as the detector had it), carries on 9 mm past two of the
// model's edges: the extension must reach past the margins it keeps by the edge and by its own
// rounded end. The model's own top does not carry on.
TEST(ObjectLookAlike, ContinuationSeesAWiderTopAtHighNoise) {
  const Superquadric model = test::box_model();  // 25, 25, 50
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 0.8);
  const auto top = [&](double half_width) {
    std::vector<Eigen::Vector3d> pts;
    for (double x = -half_width; x <= half_width; x += 1.0) {
      for (double y = -half_width; y <= half_width; y += 1.0) {
        pts.emplace_back(x, y, 50.0 + noise(rng));
      }
    }
    return pts;
  };
  const std::vector<Eigen::Vector3d> own = top(23.0), wider = top(29.5);
  const KdTree own_tree(own), wider_tree(wider);
  ContinuationOptions o;
  o.band_mm = 3.0 * 0.8;
  const Eigen::Isometry3d centre = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d corner = Eigen::Isometry3d::Identity();
  corner.translation() = Eigen::Vector3d(4.5, 4.5, 0.0);
  EXPECT_LT(surface_continuation(model, centre, own, own_tree, o).share, 0.005);
  EXPECT_GT(surface_continuation(model, corner, wider, wider_tree, o).share, 0.05);
}

// A neighbour whose top stands level with the model's, 9 mm past its edge: at 0.8 mm noise the
// window the continuation looks in begins 4.6 mm past the edge and holds the neighbour's first
// millimetres, but the strip between is bare, so the model's top does not carry on (a mallet's
// head by a box as tall was rejected so). Nor at 5.5 mm past, where the neighbour's nearest
// points lie just past the window's start (a true box of the pan-tilt tuning scenes was rejected
// so). The wider box's top, which runs on from the edge, still does.
TEST(ObjectLookAlike, ContinuationDoesNotCrossABareStrip) {
  const Superquadric model = test::box_model();  // 25, 25, 50
  for (double strip : {9.0, 5.5}) {
    std::vector<Eigen::Vector3d> beside, wider;
    for (double y = -25.0; y <= 25.0; y += 0.5) {
      for (double x = -25.0; x <= 60.0; x += 0.5) {
        wider.emplace_back(x, y, 50.0);
        if (x <= 25.0 || x >= 25.0 + strip) beside.emplace_back(x, y, 50.0);
      }
    }
    const KdTree beside_tree(beside), wider_tree(wider);
    ContinuationOptions o;
    o.band_mm = 3.0 * 0.8;
    const Eigen::Isometry3d centre = Eigen::Isometry3d::Identity();
    const Continuation across = surface_continuation(model, centre, beside, beside_tree, o);
    EXPECT_GT(across.surface, 3000) << strip;
    EXPECT_EQ(across.continuing, 0) << strip;
    EXPECT_GT(surface_continuation(model, centre, wider, wider_tree, o).share, 0.02) << strip;
  }
}

// Varied tuning scenes (sim/varied_scene.hpp) at 0.6-0.8 mm noise with a standing look-alike
// 18-20 % wider than the box: fitted on one corner of its top, it reads the model's size from the
// faces it shows, and only its top carrying on past the model's edges tells it apart (the
// detector took it once its size evidence changed and before the continuation reached past the
// noise band). Seed 169, and seed 134, whose box stands a quarter hidden behind a wall.
TEST(ObjectLookAlike, FindsTheBoxNotAWiderOneAtHighNoise) {
  for (std::uint64_t seed : {134u, 169u}) {
    test::expect_varied_target_found(sim::VariedTarget::kBox, seed);
  }
}

// Lying look-alike boxes 12.6 and 7.7 % longer than the model at 0.81 and 0.77 mm noise
// (pan-tilt object-free seeds 379 and 422, the model a box), fitted with its ends 4-6 mm short of
// theirs: the window the continuation looked in began 5.9 mm past an end, and the boxes were
// taken for the model. From 1.5 bands on it holds their walls' last millimetres.
TEST(ObjectLookAlike, ALyingBoxLongerByAFewBandsIsNotTheBox) {
  for (std::uint64_t seed : {379u, 422u}) {
    const sim::VariedScene s = test::object_free_scene(seed, true);
    ASSERT_EQ(s.model.name, "box") << "seed " << seed;
    const ObjectDetectResult r = test::detect_in(s, seed);
    EXPECT_FALSE(r.found()) << "seed " << seed << ": " << test::describe_rejections(r);
  }
}

// A true box whose neighbour's face stands level with its own 5.7 mm past its edge (pan-tilt
// tuning seed 177, 0.88 mm noise): the neighbour's nearest points lay just inside the window the
// continuation looks in, and the box was rejected for carrying on (0.014 against 0.01).
TEST(ObjectLookAlike, FindsAPanTiltBoxWithANeighbourLevelJustPastItsEdge) {
  test::expect_varied_target_found(sim::VariedTarget::kBox, 177, true);
}

// Varied tuning scenes with a can 14-16 % shorter lying on the table: the model fitted flush with
// one of its ends reaches 14-16 mm past the other, farther than the first scale of the open-end
// check looks (a fifth of the half-length), whose rings farther in were bare as well, and was
// taken for the cylinder (0.9 mm noise, camera +y, 47 deg, seed 85; 0.16 mm, camera -y, 30 deg,
// seed 215, whose cylinder stands under an overhang).
TEST(ObjectLookAlike, FindsTheCylinderNotAShorterLyingCan) {
  for (std::uint64_t seed : {85u, 215u}) {
    test::expect_varied_target_found(sim::VariedTarget::kCylinder, seed);
  }
}

// Pan-tilt tuning scenes with a lying look-alike can whose differing end lies in its own shadow:
// 7 % longer (0.45 mm noise, seed 166), 14 % shorter (0.45 mm, seed 268). Fitted by the model it
// passed every check, its length left open by the points, and was taken for the cylinder, which
// stood elsewhere with both ends seen. The cylinder whose size the points verify is preferred.
TEST(ObjectLookAlike, PrefersTheCylinderWhoseLengthIsSeenToALookAlikeWithAnEndInShadow) {
  for (std::uint64_t seed : {166u, 268u}) {
    test::expect_varied_target_found(sim::VariedTarget::kCylinder, seed, true);
  }
}

// Pan-tilt tuning scenes (301-600) with standing look-alikes 7 and 10 % wider than the box and as
// tall, seen on their tops and on a flank the head grazed (0.84 mm noise, seed 595; 0.70 mm, seed
// 339, whose box stands under an overhang). The first size fit read them 7 % wide to 0.3 %; the
// second, asked to confirm it, ran to its bound and left the width open, and they were taken for
// the box. A width the second fit leaves open does not overrule the first's.
TEST(ObjectLookAlike, AStandingBoxWiderBySevenPerCentIsNotTheBox) {
  for (std::uint64_t seed : {595u, 339u})
    test::expect_varied_target_found(sim::VariedTarget::kBox, seed, true);
}

// A can standing among the clutter, 27 mm in radius and 98 mm tall, beside a box (25 x 25 x 50
// half-sizes) lying behind a wall (pan-tilt tuning seed 269, 0.61 mm noise). Fitted by the box,
// the can's points lie within the noise's allowance of its surface and passed every other check;
// a round section fits them better (rms 1.43 times less), and the box behind the wall is the one
// found.
TEST(ObjectLookAlike, ACanIsNotTakenForABoxOfItsSize) {
  test::expect_varied_target_found(sim::VariedTarget::kBox, 269, true);
}

// A standing can of the box's width alone on the table at 0.6 mm noise, and a box alone: the can
// is not taken for the box, the box is found.
TEST(ObjectLookAlike, ACanAloneIsNotTheBoxAtHighNoise) {
  const Superquadric can{26.5, 26.5, 49.0, 0.1, 1.0, 0, 0};
  const ObjectModel box = test::single("box", test::box_model());
  for (const StripeGeometry& g : kGeometries) {
    const sim::VariedScene s =
        scan({part("can", can, {0, 60, can.a3}, Eigen::Vector3d::UnitZ())}, {}, box, g, 21, 0.6);
    const ObjectDetectResult r = detect(s, 21);
    EXPECT_FALSE(r.found()) << g.triangulation_deg << " deg, side " << g.side << ": "
                            << describe(r);
    const Superquadric& b = test::box_model();
    const sim::VariedScene t =
        scan({part("box", b, {0, 60, b.a3}, Eigen::Vector3d::UnitZ())}, {0}, box, g, 21, 0.6);
    EXPECT_TRUE(detect(t, 21).found()) << g.triangulation_deg << " deg, side " << g.side;
  }
}

// A varied tuning scene whose mallet head lies with one cap 8 mm from a clutter box as tall as
// the head (seed 258): the box's top extended the head's side wall past its cap and the true
// head was rejected, until only a continuation that runs on from the face counted.
TEST(ObjectLookAlike, FindsTheMalletHeadByABoxAsTall) {
  test::expect_varied_target_found(sim::VariedTarget::kMallet, 258);
}

}  // namespace object_lookalike_test
}  // namespace rangefit
