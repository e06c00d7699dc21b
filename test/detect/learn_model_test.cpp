// Model learning (detect/model_learning.hpp) on simulated teach-in scans: the thesis objects and
// random superquadrics alone on the table, one view or two (front and back, fused), with 0.05 mm
// noise; the learnt sizes and shapes against the truth, and the learnt model at work in the
// object detector on a different, cluttered laser-stripe scene.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <limits>
#include <numbers>
#include <random>
#include <span>
#include <string>

#include "detect/learn/model_learning.hpp"
#include "detect/object/object_detector.hpp"
#include "io/object_model_file.hpp"
#include "sim/varied_scene.hpp"
#include "test/detect/learn_scenes.hpp"
#include "test/detect/object_scenes.hpp"

namespace rangefit {
namespace learn_model_test {

constexpr double kNoise = 0.05;

struct Learnt {
  LearnResult result;
  test::ShapeError error;
};

Learnt learn(const Superquadric& truth, std::uint64_t pose_seed, int views) {
  const std::vector<sim::ScenePart> parts = test::resting(truth, pose_seed);
  const std::vector<Eigen::Vector3d> scan = test::teach_scan(parts, views, kNoise, pose_seed);
  Learnt l;
  l.result = learn_model(scan);
  if (l.result.learnt()) {
    const LearntPart& p = l.result.parts.at(0);
    l.error = test::shape_error(p.shape, p.T_world_part, truth, parts[0].T_world_part);
  } else {
    l.error.size = l.error.shape = 1e9;
  }
  return l;
}

std::string describe(const Learnt& l) {
  if (!l.result.learnt()) return to_string(l.result.reason);
  const Superquadric& s = l.result.parts[0].shape;
  char buf[240];
  std::snprintf(
      buf, sizeof buf,
      "learnt %.2f %.2f %.2f e %.3f %.3f k %.3f %.3f: size %.4f shape %.4f, residual %.3f "
      "mm, visible %.2f, %.0f ms",
      s.a1, s.a2, s.a3, s.eps1, s.eps2, s.kx, s.ky, l.error.size, l.error.shape,
      l.result.parts[0].residual_mm, l.result.parts[0].visible_share, l.result.total_ms);
  return buf;
}

struct ThesisCase {
  const char* name;
  Superquadric truth;
  double size_one, shape_one;  // what one view reaches (the goal: 2 %, 0.1)
  double size_two, shape_two;  // what two views reach (the goal: 1 %, 0.05)
};

// Every goal is met, the cone's too. Near its apex the surface has next to no area and next to
// no points (the highest point seen is 1.5 mm below the tip), so the sides fix where they meet
// (a3 / |k|) but a3 and the taper slide along that valley; with the 0.05 mm noise the fit
// prefers a blunted tip (a3 1.9 % short from two views), and the refit with the taper on its
// bound is kept when the points do not show the blunted tip clearly (model_learning.cpp).
const ThesisCase kThesis[] = {
    {"cylinder", sim::cylinder_model(), 0.02, 0.1, 0.01, 0.05},
    {"box", sim::box_model(), 0.02, 0.1, 0.01, 0.05},
    {"sphere", sim::sphere_model(), 0.02, 0.1, 0.01, 0.05},
    {"cone", sim::cone_model(), 0.02, 0.1, 0.01, 0.05},
};

#if defined(__SANITIZE_ADDRESS__)
constexpr std::size_t kThesisCases = 2;  // ASan+UBSan runs ~10x slower: cylinder and box only
#else
constexpr std::size_t kThesisCases = std::size(kThesis);
#endif

TEST(LearnModel, LearnsTheThesisObjectsFromOneView) {
  for (const ThesisCase& c : std::span(kThesis).first(kThesisCases)) {
    const Learnt l = learn(c.truth, 3, 1);
    std::printf("  %s, one view: %s\n", c.name, describe(l).c_str());
    ASSERT_TRUE(l.result.learnt()) << c.name << ": " << describe(l);
    EXPECT_LE(l.error.size, c.size_one) << c.name << ": " << describe(l);
    EXPECT_LE(l.error.shape, c.shape_one) << c.name << ": " << describe(l);
    // A single view sees well under all of the surface, and the points lie on the fit: their
    // rms distance from it is the scan's noise (the radial distance read the cone's 0.05 mm
    // noise as 0.1 mm).
    EXPECT_GT(l.result.parts[0].visible_share, 0.25) << c.name;
    EXPECT_LT(l.result.parts[0].visible_share, 0.65) << c.name;
    EXPECT_LT(l.result.parts[0].residual_mm, 1.3 * kNoise) << c.name;
  }
}

// One view of the cone shows the near half of its round base: started in the middle of what was
// seen, the fits ended half a radius in front of its axis (7-101 % size errors on these yaws);
// starts completing the section on either side (detect/learn/learn_start.cpp) find it.
TEST(LearnModel, LearnsTheConeFromOneViewWhateverItsYaw) {
#if defined(__SANITIZE_ADDRESS__)
  constexpr std::uint64_t kLast = 4;  // ASan+UBSan runs ~10x slower
#else
  constexpr std::uint64_t kLast = 7;
#endif
  for (std::uint64_t seed = 4; seed <= kLast; ++seed) {
    const Learnt l = learn(sim::cone_model(), seed, 1);
    std::printf("  cone, seed %llu, one view: %s\n", static_cast<unsigned long long>(seed),
                describe(l).c_str());
    ASSERT_TRUE(l.result.learnt()) << seed;
    EXPECT_LE(l.error.size, 0.02) << seed << ": " << describe(l);
    EXPECT_LE(l.error.shape, 0.1) << seed << ": " << describe(l);
  }
}

TEST(LearnModel, LearnsTheThesisObjectsFromTwoFusedViews) {
  for (const ThesisCase& c : std::span(kThesis).first(kThesisCases)) {
    const Learnt one = learn(c.truth, 3, 1), two = learn(c.truth, 3, 2);
    std::printf("  %s, two views: %s\n", c.name, describe(two).c_str());
    ASSERT_TRUE(two.result.learnt()) << c.name << ": " << describe(two);
    EXPECT_LE(two.error.size, c.size_two) << c.name << ": " << describe(two);
    EXPECT_LE(two.error.shape, c.shape_two) << c.name << ": " << describe(two);
    // The second view shows more of the surface.
    EXPECT_GT(two.result.parts[0].visible_share, one.result.parts[0].visible_share + 0.1) << c.name;
  }
}
// Random superquadrics (eps 0.1-1.9, taper -0.5..0.5, sizes 20-60 mm) resting on the table,
// each with its own pose; seeds 1.. are the tuning set, 1000001.. held out (only reported).
struct RandomStats {
  int within = 0;  // of `seeds`, within the size and shape goals
  double worst_size = 0.0, worst_shape = 0.0;
};

RandomStats learn_random(std::uint64_t first_seed, int seeds, int views, double size_goal,
                         double shape_goal) {
  RandomStats s;
  for (int i = 0; i < seeds; ++i) {
    const std::uint64_t seed = first_seed + static_cast<std::uint64_t>(i);
    const Learnt l = learn(test::random_superquadric(seed), seed, views);
    s.worst_size = std::max(s.worst_size, l.error.size);
    s.worst_shape = std::max(s.worst_shape, l.error.shape);
    if (l.error.size <= size_goal && l.error.shape <= shape_goal) ++s.within;
    std::printf("  seed %llu, %d view(s): %s\n", static_cast<unsigned long long>(seed), views,
                describe(l).c_str());
  }
  return s;
}

#if defined(__SANITIZE_ADDRESS__)
constexpr int kRandomSeeds = 2;  // ASan+UBSan runs ~10x slower
#else
constexpr int kRandomSeeds = 4;
#endif

TEST(LearnModel, LearnsRandomSuperquadricsFromOneView) {
  const RandomStats s = learn_random(1, kRandomSeeds, 1, 0.02, 0.1);
  EXPECT_GE(s.within, kRandomSeeds - 1);
  EXPECT_LE(s.worst_size, 0.1);
  EXPECT_LE(s.worst_shape, 0.2);
}

TEST(LearnModel, LearnsRandomSuperquadricsFromTwoViews) {
  const RandomStats s = learn_random(1, kRandomSeeds, 2, 0.01, 0.05);
  EXPECT_GE(s.within, kRandomSeeds - 1);
  EXPECT_LE(s.worst_size, 0.1);
  EXPECT_LE(s.worst_shape, 0.2);
}

TEST(LearnModel, HeldOutRandomSuperquadricsAreReported) {
  const RandomStats one = learn_random(sim::kHeldOutSeedBase, kRandomSeeds, 1, 0.02, 0.1);
  const RandomStats two = learn_random(sim::kHeldOutSeedBase, kRandomSeeds, 2, 0.01, 0.05);
  std::printf(
      "held out: one view %d/%d within 2 %%/0.1 (worst %.4f, %.4f), two views %d/%d "
      "within 1 %%/0.05 (worst %.4f, %.4f)\n",
      one.within, kRandomSeeds, one.worst_size, one.worst_shape, two.within, kRandomSeeds,
      two.worst_size, two.worst_shape);
  EXPECT_GE(one.within, kRandomSeeds / 2);
  EXPECT_GE(two.within, kRandomSeeds / 2);
}

}  // namespace learn_model_test
}  // namespace rangefit

namespace rangefit {
namespace learn_model_test {

// Two parts: the mallet (head 30,30,56 across the end of the shaft 12,10,120, centres 170 mm
// apart) lying on the table, seen from the front and from behind.
TEST(LearnModel, LearnsTheMalletAsHeadAndShaftWithTheirLink) {
  std::mt19937_64 rng(4);
  sim::TableObject mallet = sim::resting_mallet("mallet", rng);
  sim::place(mallet, test::kObjectX, test::kObjectY, 0.4);
  const std::vector<Eigen::Vector3d> scan = test::teach_scan(mallet.parts, 2, kNoise, 4);
  LearnOptions o;
  o.parts = 2;
  const LearnResult r = learn_model(scan, o);
  ASSERT_TRUE(r.learnt()) << to_string(r.reason);
  ASSERT_EQ(r.parts.size(), 2u);
  ASSERT_EQ(r.model.links.size(), 1u);
  const ObjectModel truth = sim::mallet_model();
  for (std::size_t k = 0; k < 2; ++k) {
    const Superquadric& s = r.parts[k].shape;
    std::printf(
        "  part %zu: %.2f %.2f %.2f e %.3f %.3f k %.3f %.3f, %zu points, residual %.3f mm\n", k,
        s.a1, s.a2, s.a3, s.eps1, s.eps2, s.kx, s.ky, r.parts[k].points, r.parts[k].residual_mm);
  }
  std::printf(
      "  link: %.2f deg, %.2f mm, bearings %.2f %.2f deg (truth 90, 170, 90 0), %.0f ms\n",
      r.model.links[0].angle_rad * 180.0 / std::numbers::pi, r.model.links[0].distance_mm,
      r.model.links[0].bearing_rad.value_or(std::array<double, 2>{})[0] * 180.0 / std::numbers::pi,
      r.model.links[0].bearing_rad.value_or(std::array<double, 2>{})[1] * 180.0 / std::numbers::pi,
      r.total_ms);
  // Part 0 is the larger: the head.
  for (std::size_t k = 0; k < 2; ++k) {
    const test::ShapeError e =
        test::shape_error(r.parts[k].shape, r.parts[k].T_world_part, truth.parts[k].shape,
                          mallet.parts[k].T_world_part);
    EXPECT_LE(e.size, 0.02) << k;
    EXPECT_LE(e.shape, 0.1) << k;
  }
  EXPECT_NEAR(r.model.links[0].angle_rad, std::numbers::pi / 2.0, 0.02);
  EXPECT_NEAR(r.model.links[0].distance_mm, 170.0, 1.0);
  // Where the shaft sits on the head: in its middle plane, pointing at it.
  ASSERT_TRUE(r.model.links[0].bearing_rad.has_value());
  EXPECT_NEAR((*r.model.links[0].bearing_rad)[0], std::numbers::pi / 2.0, 0.02);
  EXPECT_NEAR((*r.model.links[0].bearing_rad)[1], 0.0, 0.02);
}

}  // namespace learn_model_test
}  // namespace rangefit

namespace rangefit {
namespace learn_model_test {

// The starts are fitted on several threads: the model is the same, to the last bit, on one
// thread or three (the cone, whose refits after the starts also run).
TEST(LearnModel, TheSameModelOnAnyNumberOfThreads) {
  const std::vector<sim::ScenePart> parts = test::resting(sim::cone_model(), 3);
  const std::vector<Eigen::Vector3d> scan = test::teach_scan(parts, 1, kNoise, 3);
  LearnOptions one, three;
  one.threads = 1;
  three.threads = 3;
  const LearnResult a = learn_model(scan, one), b = learn_model(scan, three);
  ASSERT_TRUE(a.learnt()) << to_string(a.reason);
  ASSERT_TRUE(b.learnt()) << to_string(b.reason);
  const Superquadric &sa = a.parts[0].shape, &sb = b.parts[0].shape;
  EXPECT_EQ(std::vector<double>({sa.a1, sa.a2, sa.a3, sa.eps1, sa.eps2, sa.kx, sa.ky}),
            std::vector<double>({sb.a1, sb.a2, sb.a3, sb.eps1, sb.eps2, sb.kx, sb.ky}));
  EXPECT_TRUE(a.parts[0].T_world_part.matrix() == b.parts[0].T_world_part.matrix());
  EXPECT_EQ(a.starts, b.starts);
}

TEST(LearnModel, EmptyTableAndBadOptionsAreReasonsNotCrashes) {
  EXPECT_EQ(learn_model({}).reason, LearnReason::kEmptyCloud);
  // A bare table: the plane goes, nothing is left.
  const std::vector<Eigen::Vector3d> table = test::teach_scan({}, 1);
  EXPECT_EQ(learn_model(table).reason, LearnReason::kNoObject);
  LearnOptions three;
  three.parts = 3;
  EXPECT_EQ(learn_model(table, three).reason, LearnReason::kInvalidOptions);
  // Non-finite points are dropped by the readers; a handful of points is too few to fit.
  std::vector<Eigen::Vector3d> few(10, Eigen::Vector3d(1, 2, 3));
  LearnOptions no_plane;
  no_plane.segment.remove_plane = false;
  no_plane.segment.min_points = 5;
  EXPECT_EQ(learn_model(few, no_plane).reason, LearnReason::kTooFewPoints);
}

TEST(LearnModel, DegenerateCloudsAreClearReasonsNotFits) {
  LearnOptions no_plane;
  no_plane.segment.remove_plane = false;
  // All points the same: with the plane removal and without.
  const std::vector<Eigen::Vector3d> same(500, Eigen::Vector3d(100.0, 50.0, 20.0));
  EXPECT_EQ(learn_model(same).reason, LearnReason::kAllAtOnePoint);
  EXPECT_EQ(learn_model(same, no_plane).reason, LearnReason::kAllAtOnePoint);
  // On a line, exactly and with a little noise across it.
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 1e-5);
  std::vector<Eigen::Vector3d> line;
  for (int i = 0; i < 400; ++i) {
    line.emplace_back(100.0 + 0.25 * i, 50.0 + 0.1 * i + noise(rng), 20.0 - 0.05 * i);
  }
  EXPECT_EQ(learn_model(line).reason, LearnReason::kCollinear);
  EXPECT_EQ(learn_model(line, no_plane).reason, LearnReason::kCollinear);
  // A wire above the table: the table goes, the line is left.
  std::vector<Eigen::Vector3d> wire = test::teach_scan({}, 1);
  for (int i = 0; i < 400; ++i) {
    wire.emplace_back(test::kObjectX - 50.0 + 0.25 * i, test::kObjectY, 30.0);
  }
  EXPECT_EQ(learn_model(wire).reason, LearnReason::kCollinear);
  // Fewer points than the fit has unknowns, however well spread.
  std::vector<Eigen::Vector3d> few;
  for (int i = 0; i < 19; ++i) few.emplace_back(10.0 * (i % 3), 10.0 * (i % 5), 3.0 * i);
  EXPECT_EQ(learn_model(few, no_plane).reason, LearnReason::kTooFewPoints);
  // One NaN in an otherwise good teach-in scan.
  std::vector<Eigen::Vector3d> scan =
      test::teach_scan(test::resting(sim::cylinder_model(), 3), 1, kNoise, 3);
  scan[scan.size() / 2].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(learn_model(scan).reason, LearnReason::kNonFinitePoints);
  scan[scan.size() / 2].y() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(learn_model(scan).reason, LearnReason::kNonFinitePoints);
  for (const LearnReason r :
       {LearnReason::kAllAtOnePoint, LearnReason::kCollinear, LearnReason::kNonFinitePoints}) {
    EXPECT_STRNE(to_string(r), "unknown");
  }
}

}  // namespace learn_model_test
}  // namespace rangefit
