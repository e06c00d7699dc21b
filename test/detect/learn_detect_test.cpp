// A model learnt from a teach-in scan of the object alone (thesis ch. 6: "show the object once")
// finds the object in a different, cluttered laser-stripe scene (the fig. 5.18 table under a
// stripe sweep, sim/varied_scene.hpp) as often as the true model does; also after a round trip
// through a model file. The same for a daily-life object of the thesis (table 5.6: the cup,
// tapered) learnt from a laser-stripe teach-in scan (test/detect/learn_daily.hpp), found among
// other daily-life objects on a stripe-cell scan.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "detect/learn/model_learning.hpp"
#include "detect/object/object_detector.hpp"
#include "io/object_model_file.hpp"
#include "sim/varied_scene.hpp"
#include "test/detect/learn_daily.hpp"
#include "test/detect/learn_scenes.hpp"
#include "test/detect/object_scenes.hpp"
#include "test/detect/stripe_scan_fixture.hpp"

namespace rangefit {
namespace learn_detect_test {

sim::ScanSetup stripe_setup(double triangulation_deg, int side) {
  sim::ScanSetup s;
  s.triangulation_deg = triangulation_deg;
  s.camera_side = side;
  s.laser_height_mm = 600.0;
  s.step_mm = 1.0;
  s.noise_mm = 0.1;
  s.max_points = 70000;  // as test/detect/object_stripe_test.cpp: fast enough for the suite
  return s;
}

bool finds_target(const ObjectModel& model, const sim::VariedScene& s, std::uint64_t seed,
                  bool axis) {
  ObjectDetectOptions o;
  o.sensor = s.view;
  o.seed = seed;
  const ObjectDetectResult r = detect_object(model, s.cloud.points, o);
  return r.found() &&
         test::true_positive(r.instances[0].parts[0].T_world_part,
                             s.parts[static_cast<std::size_t>(s.target_parts[0])], axis);
}

ObjectModel learn_from_teach_scan(const Superquadric& truth, std::uint64_t seed) {
  const std::vector<sim::ScenePart> parts = test::resting(truth, seed);
  const LearnResult r = learn_model(test::teach_scan(parts, 1, 0.05, seed));
  EXPECT_TRUE(r.learnt()) << to_string(r.reason);
  return r.model;
}

struct Rates {
  int learnt = 0, truth = 0;
};

Rates compare(const ObjectModel& learnt, sim::VariedTarget target, bool axis) {
  // Triangulation angle, camera side, seed of the scene's noise and of the detector.
  struct Geometry {
    double triangulation_deg;
    int side;
    std::uint64_t seed;
  };
#if defined(__SANITIZE_ADDRESS__)
  constexpr Geometry kGeometries[] = {{45.0, -1, 2}};  // ASan+UBSan runs ~10x slower
#else
  constexpr Geometry kGeometries[] = {{20.0, +1, 1}, {45.0, -1, 2}};
#endif
  Rates r;
  for (const Geometry& g : kGeometries) {
    const sim::VariedScene s =
        sim::thesis_scene(target, stripe_setup(g.triangulation_deg, g.side), g.seed);
    r.learnt += finds_target(learnt, s, g.seed, axis) ? 1 : 0;
    r.truth += finds_target(s.model, s, g.seed, axis) ? 1 : 0;
  }
  return r;
}

TEST(LearnDetect, LearntCylinderIsFoundInAClutteredStripeSceneAsOftenAsTheTrueModel) {
  const ObjectModel learnt = learn_from_teach_scan(sim::cylinder_model(), 3);
  const Rates r = compare(learnt, sim::VariedTarget::kCylinder, true);
  EXPECT_GT(r.truth, 0);
  EXPECT_GE(r.learnt, r.truth);
}

TEST(LearnDetect, LearntBoxWrittenAndReadBackIsFoundAsOftenAsTheTrueModel) {
  const ObjectModel learnt = learn_from_teach_scan(sim::box_model(), 5);
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "rangefit_learn_detect_box.toml";
  io::write_object_model(file, learnt, "learnt from a simulated teach-in scan");
  const ObjectModel back = io::read_object_model(file);
  std::filesystem::remove(file);
  ASSERT_EQ(back.parts.size(), 1u);
  EXPECT_EQ(back.parts[0].shape.a1, learnt.parts[0].shape.a1);
  const Rates r = compare(back, sim::VariedTarget::kBox, true);
  EXPECT_GT(r.truth, 0);
  EXPECT_GE(r.learnt, r.truth);
}

// The cup standing among other table 5.6 objects: the sponge and a cuboid lying, the sphere, and
// a can (the table's cylinder, 25 mm across like the cup's middle but untapered and half as tall).
TEST(LearnDetect, LearntCupIsFoundAmongDailyLifeObjectsAsOftenAsTheTrueModel) {
  const std::vector<sim::DailyObject> all = sim::daily_life_objects();
  auto object = [&](const std::string& name) {
    for (const sim::DailyObject& o : all) {
      if (o.name == name) return o.model.parts[0].shape;
    }
    ADD_FAILURE() << name;
    return Superquadric{};
  };
  const sim::DailyObject cup = all[7];
  ASSERT_EQ(cup.name, "cup");
  const test::DailyLearnt taught = test::learn_daily(cup, 1, 1);
  ASSERT_TRUE(taught.result.learnt()) << to_string(taught.result.reason);
  const Superquadric& truth = cup.model.parts[0].shape;
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ(), along = Eigen::Vector3d::UnitX();
  const std::vector<sim::ScenePart> parts = {
      test::placed("cup", truth, {-50, -40, truth.a3}, up),
      test::placed("sponge", object("sponge"), {60, -60, 11}, up),
      test::placed("sphere", object("sphere"), {70, 40, 25}, up),
      test::placed("can", object("cylinder"), {-60, 70, 35}, up),
      test::placed("cuboid", object("cuboid"), {5, 75, 15}, along),
  };
  int learnt = 0, true_model = 0;
  for (const test::StripeGeometry& g : test::kStripeGeometries) {
    const std::uint64_t seed = g.side > 0 ? 1 : 2;
    const sim::VariedScene s =
        test::stripe_scan(parts, {0}, cup.model, g, seed, 0.1, test::table_cover());
    learnt += finds_target(taught.result.model, s, seed, true) ? 1 : 0;
    true_model += finds_target(cup.model, s, seed, true) ? 1 : 0;
  }
  EXPECT_GT(true_model, 0);
  EXPECT_GE(learnt, true_model);
}

}  // namespace learn_detect_test
}  // namespace rangefit
