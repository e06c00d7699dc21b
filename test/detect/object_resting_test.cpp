// Object detection of parts as they rest on the table, lying or standing, on laser-stripe scans
// with the camera on either side at two triangulation angles (sim/varied_scene.hpp
// scan_varied_scene), the sensor known: the RANSAC starts of a flat face must not leave the part
// standing through the table or on the wrong side of the face.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "detect/object/object_detector.hpp"
#include "sim/varied_scene.hpp"
#include "test/detect/object_scenes.hpp"
#include "test/detect/stripe_scan_fixture.hpp"
#include "test/detect/varied_target.hpp"

namespace rangefit {
namespace object_resting_test {

using test::kStripeGeometries;
using test::StripeGeometry;

sim::ScenePart part(const std::string& name, const Superquadric& sq, const Eigen::Vector3d& c,
                    const Eigen::Vector3d& axis) {
  return test::placed(name, sq, c, axis);
}

sim::VariedScene scan(std::vector<sim::ScenePart> parts, std::vector<int> target, ObjectModel model,
                      const StripeGeometry& g, std::uint64_t seed, double noise_mm = 0.2) {
  return test::stripe_scan(std::move(parts), std::move(target), std::move(model), g, seed,
                           noise_mm, test::table_cover());
}

ObjectDetectResult detect(const sim::VariedScene& s, std::uint64_t seed) {
  return test::detect_in(s, seed);
}

std::string describe(const ObjectDetectResult& r) {
  std::string out = to_string(r.reason);
  for (const DetectedInstance& i : r.instances) {
    for (const DetectedPart& p : i.parts) {
      out += "; found " + p.name + " at " + std::to_string(p.center().x()) + " " +
             std::to_string(p.center().y()) + " " + std::to_string(p.center().z());
    }
  }
  for (const Rejection& x : r.rejections) {
    out += std::string("; ") + to_string(x.check) + " " + std::to_string(x.value) + " at z " +
           std::to_string(x.centre.z());
  }
  return out;
}

std::string label(const StripeGeometry& g) {
  return std::to_string(g.triangulation_deg) + " deg, side " + std::to_string(g.side) + ": ";
}

// The detection is the scene part `truth` (the thesis's criterion; a sphere's axis is free).
void expect_true_positive(const ObjectDetectResult& r, const sim::ScenePart& truth, bool axis,
                          const std::string& at) {
  ASSERT_TRUE(r.found()) << at << describe(r);
  EXPECT_TRUE(test::true_positive(r.instances[0].parts[0].T_world_part, truth, axis))
      << at << describe(r);
}

// A scan of the look-alike `p` alone (seed, noise) does not give the model.
void expect_not_found_alone(const sim::ScenePart& p, const ObjectModel& model,
                            const StripeGeometry& g, std::uint64_t seed, double noise_mm,
                            const std::string& at) {
  const ObjectDetectResult r = detect(scan({p}, {}, model, g, seed, noise_mm), seed);
  EXPECT_FALSE(r.found()) << at << describe(r);
}

// A scan of the model's part `truth` beside the look-alike `other` at 0.5 mm noise gives truth.
void expect_found_beside(const sim::ScenePart& truth, const sim::ScenePart& other,
                         const ObjectModel& model, const StripeGeometry& g, std::uint64_t seed,
                         bool axis) {
  const sim::VariedScene s = scan({truth, other}, {0}, model, g, seed, 0.5);
  expect_true_positive(detect(s, seed), s.parts[0], axis, label(g));
}

// The fig. 5.18 box (25 x 25 x 50) lying on a long side, its axis oblique to the sweep, beside a
// ball: a patch of its top face fits the box standing through the table (its long axis along the
// face normal) as well as lying on it, and those starts used to win every trial.
TEST(ObjectResting, FindsABoxLyingOnItsSide) {
  for (const StripeGeometry& g : kStripeGeometries) {
    // Lying flat: the part's z along (0.8, 0.6, 0) on the table, its y up.
    Eigen::Isometry3d lying = Eigen::Isometry3d::Identity();
    lying.linear().col(2) = Eigen::Vector3d(0.8, 0.6, 0.0);
    lying.linear().col(1) = Eigen::Vector3d::UnitZ();
    lying.linear().col(0) = lying.linear().col(1).cross(lying.linear().col(2));
    lying.translation() = Eigen::Vector3d(10, -20, 25);
    const sim::VariedScene s =
        scan({{"box", test::box_model(), lying},
              part("ball", {30, 30, 30, 1, 1, 0, 0}, {-70, 80, 30}, Eigen::Vector3d::UnitZ())},
             {0}, test::single("box", test::box_model()), g, 21);
    expect_true_positive(detect(s, 21), s.parts[0], true, label(g));
  }
}

// A box 5 % taller than the model standing on its end, at 0.5 mm noise: the model fits its top
// and sides, and its size evidence from one view is weak; only that the model then stands ~5 mm
// above the table tells it apart. Beside it, the real box standing is found.
TEST(ObjectResting, ATallerBoxStandingIsNotTakenForTheBox) {
  const Superquadric taller{25, 25, 52.5, 0.1, 0.1, 0, 0};
  for (const StripeGeometry& g : kStripeGeometries) {
    expect_not_found_alone(part("taller box", taller, {0, 0, 52.5}, Eigen::Vector3d::UnitZ()),
                           test::single("box", test::box_model()), g, 22, 0.5, label(g));
    expect_found_beside(part("box", test::box_model(), {-60, 70, 50}, Eigen::Vector3d::UnitZ()),
                        part("taller box", taller, {40, -40, 52.5}, Eigen::Vector3d::UnitZ()),
                        test::single("box", test::box_model()), g, 23, true);
  }
}

// Look-alikes a little shorter than the model, standing, at 0.5 mm noise: a box 4 % smaller all
// over and a ball 4.4 % flatter (varied tuning scenes had both). The model fits their tops and
// sides as well as the noise allows and their size evidence from one view is weak; the model then
// reaches 4 mm through the table, inside the table margin, while its points place its lowest
// point to a few hundredths of a millimetre (the pose covariance): it is not resting there.
TEST(ObjectResting, AShorterBoxOrAFlatterBallIsNotTakenForTheModel) {
  const Superquadric shorter{24, 24, 48, 0.1, 0.1, 0, 0};
  const Superquadric flatter{50, 50, 47.8, 1, 1, 0, 0};
  for (const StripeGeometry& g : kStripeGeometries) {
    expect_not_found_alone(part("shorter box", shorter, {10, -20, 48}, Eigen::Vector3d::UnitZ()),
                           test::single("box", test::box_model()), g, 24, 0.5, label(g));
    expect_not_found_alone(
        part("flatter ball", flatter, {-10, 20, 47.8}, Eigen::Vector3d::UnitZ()),
        test::single("sphere", test::sphere_model()), g, 25, 0.5, label(g));
  }
}

// The true sphere beside the flatter ball is still found: the sink check holds a part to what
// its own points say, not to a fixed millimetre.
TEST(ObjectResting, FindsTheSphereBesideAFlatterBall) {
  const Superquadric flatter{50, 50, 47.8, 1, 1, 0, 0};
  for (const StripeGeometry& g : kStripeGeometries) {
    expect_found_beside(
        part("sphere", test::sphere_model(), {-65, 60, 50}, Eigen::Vector3d::UnitZ()),
        part("flatter ball", flatter, {55, -55, 47.8}, Eigen::Vector3d::UnitZ()),
        test::single("sphere", test::sphere_model()), g, 26, false);
  }
}

// Lying along the sweep, a box's or a can's caps face along it and show no points: where the part
// ends is told only by where its side wall stops. A box and a can 10-12 % shorter (varied scenes
// without the target had both) fitted by the model leave it reaching 5-6 mm past their far end,
// too few of its 200 coverage samples to count; the dense rings by each end see no surface there.
// The true box and can lying the same way are found.
TEST(ObjectResting, AShorterBoxOrCanLyingAlongTheSweepIsNotTakenForTheModel) {
  const Eigen::Vector3d along = Eigen::Vector3d::UnitY();  // the sweep's direction
  const struct {
    const char* name;
    Superquadric model, shorter;
  } cases[] = {{"box", test::box_model(), {25, 25, 44.2, 0.1, 0.1, 0, 0}},
               {"cylinder", test::cylinder_model(), {30, 30, 45.2, 0.1, 1.0, 0, 0}}};
  for (const StripeGeometry& g : kStripeGeometries) {
    for (const auto& c : cases) {
      const std::string at = std::string(c.name) + ", " + label(g);
      expect_not_found_alone(part("shorter", c.shorter, {10, -20, c.shorter.a1}, along),
                             test::single(c.name, c.model), g, 27, 0.3, at);
      const sim::VariedScene real = scan({part(c.name, c.model, {10, -20, c.model.a1}, along)},
                                         {0}, test::single(c.name, c.model), g, 28, 0.3);
      expect_true_positive(detect(real, 28), real.parts[0], true, at);
    }
  }
}

// A cone rests on the table like the untapered parts (object_hypotheses.cpp lowest_above, by its
// tapered support): a RANSAC start hung from an overhang's plate, or sunk through the table, no
// longer wins its hypothesis over one standing on the table by a smaller M. On pan-tilt tuning
// seeds 131, 274 and 289 (0.6-1.0 mm noise) the starts on the true cone had M 0.03-0.09 and those
// on plates and look-alikes 0.005-0.02, and no hypothesis of 32 came out on the cone.
TEST(ObjectResting, APanTiltConesRestingStartsWinOverStartsOffTheTable) {
  for (std::uint64_t seed : {131u, 274u, 289u}) {
    test::expect_varied_target_found(sim::VariedTarget::kCone, seed, true);
  }
}

// A part confirmed standing square on the table is reported set down on it: the table's plane
// places its height better than the part's own points. Pan-tilt tuning cones 148 and 206
// (0.9-1.0 mm noise, 38-43 % under an overhang, the lower flank hidden) were fitted 2.8 mm and
// more above the table and came out over 3 mm off; set down, each is within a millimetre in
// height.
TEST(ObjectResting, APanTiltConeFittedAboveTheTableIsReportedStandingOnIt) {
  for (std::uint64_t seed : {148u, 206u}) {
    sim::VariedSceneOptions so;
    so.target = sim::VariedTarget::kCone;
    so.pan_tilt = true;
    const sim::VariedScene s = sim::make_varied_scene(so, seed);
    const ObjectDetectResult r = test::detect_in(s, seed);
    ASSERT_TRUE(r.found()) << "seed " << seed << ": " << test::describe_rejections(r);
    const Eigen::Isometry3d& T = r.instances[0].parts[0].T_world_part;
    const sim::ScenePart& truth = s.parts[static_cast<std::size_t>(s.target_parts[0])];
    EXPECT_TRUE(test::true_positive(T, truth, true)) << "seed " << seed;
    EXPECT_LT(std::abs(T.translation().z() - truth.T_world_part.translation().z()), 1.0)
        << "seed " << seed << ": " << T.translation().transpose();
  }
}

}  // namespace object_resting_test
}  // namespace rangefit
