// The shipped STL scenes (data/scenes/*_stl.toml): they load through the STL path, and the
// detectors of thesis ch. 4 and 5 find their targets in simulated scans of them, fused from the
// raw HAL streams as on the cell (one test per sensor).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "detect/bore/bore_detector.hpp"
#include "detect/object/object_detector.hpp"
#include "fusion/css_assembler.hpp"
#include "fusion/profile_assembler.hpp"
#include "sim/analytic_shapes.hpp"
#include "sim/css_simulator.hpp"
#include "sim/mesh_export.hpp"
#include "sim/pan_tilt_head.hpp"
#include "sim/scene_loader.hpp"
#include "sim/sim_clock.hpp"
#include "sim/stripe_cell.hpp"
#include "sim_test_scans.hpp"

namespace rangefit::sim {
namespace stl_scenes_test {

using std::chrono::milliseconds;

std::string scene_path(const std::string& name) {
  return std::string(RANGEFIT_SOURCE_DIR) + "/data/scenes/" + name;
}

Eigen::Vector3d found_sphere(const std::vector<Eigen::Vector3d>& points, double radius) {
  const ObjectModel sphere{
      "sphere", {{"sphere", Superquadric{radius, radius, radius, 1.0, 1.0, 0.0, 0.0}}}, {}};
  ObjectDetectOptions opt;
  opt.seed = 3;
  const ObjectDetectResult r = detect_object(sphere, points, opt);
  EXPECT_TRUE(r.found()) << to_string(r.reason);
  return r.found() ? r.instances[0].parts[0].center() : Eigen::Vector3d::Constant(1e9);
}

TEST(StlScenes, TessellatedPrimitivesHaveTheirVerticesOnTheExactSurface) {
  const Superquadric tapered{30.0, 20.0, 50.0, 0.5, 1.0, 0.3, -0.2};
  const Shape shapes[] = {BoxShape{Eigen::Vector3d(10.0, 20.0, 30.0)}, CylinderShape{5.0, 12.0},
                          SphereShape{7.0}, PlaneShape{40.0, 30.0}, SuperquadricShape{tapered}};
  for (const Shape& shape : shapes) {
    const io::TriangleMesh m = tessellate(shape, 12, 24);
    ASSERT_GE(m.triangles.size(), 2u);
    for (const auto& v : m.vertices) {
      if (const auto* q = std::get_if<SuperquadricShape>(&shape)) {
        ASSERT_NEAR(metric_world(q->model, Eigen::Isometry3d::Identity(), v), 1.0, 1e-6);
      } else {
        ASSERT_LT(surface_distance(shape, Eigen::Isometry3d::Identity(), v), 1e-9);
      }
    }
  }
  EXPECT_TRUE(tessellate(SphereShape{1.0}, 1, 24).triangles.empty()) << "too coarse a grid";
}

TEST(StlScenes, BoreTruthOfAMeshSceneIsCheckedOnLoad) {
  const char* good = R"([[object]]
name = "t"
type = "plane"
[[bore]]
name = "b"
diameter = 12
opening = [1, 2, 3]
axis = [0, 0, -2]
)";
  const Scene s = parse_scene(good, "good.toml", ".");
  ASSERT_EQ(s.bores.size(), 1u);
  EXPECT_EQ(s.bores[0].axis, Eigen::Vector3d(0, 0, -1));
  EXPECT_EQ(s.bores[0].kind, "straight");
  try {
    parse_scene(std::string(good) +
                    "[[bore]]\nname = \"z\"\ndiameter = 3\nopening = [0, 0, 0]\n"
                    "axis = [0, 0, 0]\n",
                "bad.toml", ".");
    FAIL() << "expected SceneError";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("bore[1].axis: must not be the zero vector"),
              std::string::npos)
        << e.what();
  }
}

TEST(StlScenes, EachLoadsFromSmallStlFilesLikeItsPrimitiveScene) {
  const std::pair<const char*, const char*> pairs[] = {
      {"bore_plate_stl.toml", "bore_plate.toml"},
      {"table_top_fig5_18_stl.toml", "table_top_fig5_18.toml"},
      {"cluttered_mallet_stl.toml", "cluttered_mallet.toml"}};
  for (const auto& [stl, primitive] : pairs) {
    const Scene s = load_scene(scene_path(stl));
    const Scene p = load_scene(scene_path(primitive));
    ASSERT_EQ(s.objects.size(), p.objects.size()) << stl;
    EXPECT_EQ(s.bores.size(), p.bores.size()) << stl;
    int meshes = 0;
    for (const auto& o : s.objects) {
      const auto* m = std::get_if<MeshShape>(&o.shape);
      if (!m) continue;
      ++meshes;
      EXPECT_GT(m->mesh.triangles.size(), 10u) << stl << " " << o.name;
      EXPECT_LT(std::filesystem::file_size(scene_path(m->source)), 200u * 1024u) << m->source;
    }
    EXPECT_GE(meshes, 1) << stl;
  }
  EXPECT_THROW(load_scene(scene_path("no_such_scene_stl.toml")), SceneError);
}

TEST(StlScenes, CssScanOfTheStlBorePlateGivesTheBoreDetectorItsBore) {
  const Scene scene = load_scene(scene_path("bore_plate_stl.toml"));
  const RayCaster caster(scene);
  SimClock clock;
  CssScanOptions o;
  o.seed = 12;
  o.css_faults.range_noise_sigma_mm = 0.06;  // thesis 4.2.1
  CssRig rig(scene, caster, o, clock);
  fusion::CssFusionConfig config;
  config.geometry = o.geometry;
  fusion::CssAssembler assembler(config);
  assembler.begin_scan();
  ASSERT_TRUE(rig.css().start());
  ASSERT_TRUE(rig.joint().start());
  std::vector<hal::CssRevolution> revs;
  std::vector<hal::JointSample> joints;
  while (clock.now() < rig.scan_end() + milliseconds(300)) {
    revs.clear();
    joints.clear();
    rig.joint().read(joints, milliseconds(100));
    rig.css().read(revs, milliseconds(0));
    for (const auto& j : joints) assembler.add_joint(j);
    for (const auto& r : revs) assembler.add_revolution(r);
  }
  const fusion::FusedScan scan = assembler.finish();
  ASSERT_FALSE(scan.bad) << scan.reason;
  ASSERT_GT(scan.cloud.size(), 50000u);
  const BoreTruth* truth = nullptr;
  for (const auto& b : scene.bores) truth = b.name == "straight_12" ? &b : truth;
  ASSERT_NE(truth, nullptr);
  BorePrior prior;
  prior.entrance = truth->opening_mm + Eigen::Vector3d(0.6, 0.4, 0.0);  // CAD vs. real part
  prior.axis = -truth->axis;
  prior.radius = 0.5 * truth->diameter_mm;
  const BoreResult r = detect_bore(scan.cloud, prior);
  ASSERT_TRUE(r.found);
  EXPECT_LT((r.entrance - truth->opening_mm).norm(), 0.3);  // thesis: +-0.3 mm
  EXPECT_NEAR(r.radius, 6.0, 0.1);
}

TEST(StlScenes, StripeScanOfTheStlTableTopGivesTheObjectDetectorItsSphere) {
  const Scene scene = load_scene(scene_path("table_top_fig5_18_stl.toml"));
  const RayCaster caster(scene);
  const fusion::FusedScan scan = testing::stripe_cell_scan(scene, caster, 5);
  ASSERT_FALSE(scan.bad) << scan.reason;
  const auto points = testing::thinned(scan, scene.mounts.T_scene_stripe);
  ASSERT_GT(points.size(), 50000u);
  // Thesis 5.2.2: a true positive lies within 3 mm of the ground truth (table 5.3).
  EXPECT_LT((found_sphere(points, 50.0) - Eigen::Vector3d(160.0, 65.0, 50.0)).norm(), 3.0);
}

TEST(StlScenes, PanTiltScanOfTheStlClutteredTableGivesTheObjectDetectorItsBall) {
  const Scene scene = load_scene(scene_path("cluttered_mallet_stl.toml"));
  const RayCaster caster(scene);
  SimClock clock;
  PanTiltOptions o;
  o.seed = 8;
  PanTiltHead head(scene, caster, o, clock);
  fusion::PanTiltFusionConfig config;
  config.geometry = o.geometry;
  fusion::PanTiltAssembler assembler(config);
  assembler.begin_scan();
  ASSERT_TRUE(head.angles().start());
  ASSERT_TRUE(head.ranger().start());
  std::vector<hal::RangerProfile> profiles;
  std::vector<hal::PanTiltSample> angles;
  while (clock.now() < head.sweep_end()) {
    profiles.clear();
    angles.clear();
    head.angles().read(angles, milliseconds(100));
    head.ranger().read(profiles, milliseconds(0));
    for (const auto& s : angles) assembler.add_pan_tilt(s);
    for (const auto& p : profiles) assembler.add_profile(p);
  }
  const fusion::FusedScan scan = assembler.finish();
  ASSERT_FALSE(scan.bad) << scan.reason;
  const auto points = testing::thinned(scan, scene.mounts.T_scene_pantilt);
  ASSERT_GT(points.size(), 20000u);
  EXPECT_LT((found_sphere(points, 35.0) - Eigen::Vector3d(40.0, 60.0, 35.0)).norm(), 3.0);
}

}  // namespace stl_scenes_test
}  // namespace rangefit::sim
