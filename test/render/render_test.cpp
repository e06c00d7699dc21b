// Pictures of known scenes with a fixed camera: the model's outline must be drawn where the
// geometry puts it, over the scan's points, and nothing where there is neither.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "render/colour_map.hpp"
#include "render/model_geometry.hpp"
#include "render/render.hpp"
#include "sim/superquadric_raycast.hpp"
#include "test/render/picture_checks.hpp"

namespace rangefit::render {
namespace {

constexpr double kPi = std::numbers::pi;

using test::clean_bore;
using test::colour_near;

// RANGEFIT_RENDER_TEST_DIR=DIR keeps the pictures for a look.
void keep(const Image& image, const std::string& name) {
  if (const char* dir = std::getenv("RANGEFIT_RENDER_TEST_DIR")) {
    std::string error;
    EXPECT_TRUE(write_png(image, std::string(dir) + "/" + name + ".png", &error)) << error;
  }
}

Rgb pixel(const Image& image, const Eigen::Vector2d& p) {
  return image.at(static_cast<int>(std::floor(p.x())), static_cast<int>(std::floor(p.y())));
}

TEST(Render, BoreEntranceRingLiesOnTheHoleEdgeInBothViews) {
  const sim::SyntheticBoreScan scan = clean_bore();
  const sim::SyntheticBoreTruth& t = scan.truth;
  Drawing drawing;
  drawing.bores.push_back({t.entrance, t.axis, t.radius, t.plane_normal, 6.0 * t.radius});
  RenderOptions o;
  o.panel_width = o.panel_height = 400;
  o.toward_sensor = t.axis;
  o.look_at = t.entrance;
  o.px_per_mm = 10.0;
  const Rendering r = render_scan(scan.cloud, drawing, o);
  keep(r.image, "bore_fixed_camera");
  ASSERT_EQ(r.image.width, 800);
  ASSERT_GT(r.image.height, 400);

  for (const Panel* panel : {&r.sensor, &r.top}) {
    SCOPED_TRACE(panel->title);
    // The panel centre is the entrance, and the entrance is marked there.
    EXPECT_NEAR((panel->pixel(t.entrance) - Eigen::Vector2d(panel->x0 + 200, 200)).norm(), 0.0,
                1e-9);
    EXPECT_TRUE(colour_near(r.image, panel->pixel(t.entrance), kEntranceColour, 2));
    // The entrance ring: 5 mm at 10 px/mm around the centre (the plate is flat and both views
    // look along the bore axis, which is the plate normal here).
    for (int k = 0; k < 12; ++k) {
      const double w = 2.0 * kPi * (k + 0.5) / 12.0;
      const Eigen::Vector2d on_ring =
          Eigen::Vector2d(panel->x0 + 200, 200) + 50.0 * Eigen::Vector2d(std::cos(w), std::sin(w));
      EXPECT_TRUE(colour_near(r.image, on_ring, kModelColour)) << "angle " << w;
    }
    // The plate around it is drawn as points (not background, not model lines)...
    const Eigen::Vector2d on_plate(panel->x0 + 200 + 85.0, 200 + 20.0);
    EXPECT_NE(pixel(r.image, on_plate), kBackground);
    EXPECT_FALSE(colour_near(r.image, on_plate, kModelColour, 0));
    // ... and the scan ends 13 mm from the axis: 19 mm out is background.
    EXPECT_EQ(pixel(r.image, Eigen::Vector2d(panel->x0 + 200 + 190.0, 200.5)), kBackground);
  }
}

TEST(Render, SuperquadricOutlineAndDistanceColours) {
  sim::ScenePart part;
  part.name = "ellipsoid";
  part.model.a1 = 40.0;
  part.model.a2 = 25.0;
  part.model.a3 = 15.0;
  part.T_world_part.translation() = Eigen::Vector3d(150.0, 100.0, 15.0);
  sim::SceneView view;
  const sim::RenderedScene scene = sim::render_scene({part}, view);
  ASSERT_GT(scene.cloud.size(), 1000u);

  Drawing drawing;
  drawing.parts.push_back({part.name, part.model, part.T_world_part});
  RenderOptions o;
  o.panel_width = o.panel_height = 400;
  o.toward_sensor = Eigen::Vector3d::UnitZ();  // both panels from above: x right, y up
  o.look_at = part.T_world_part.translation();
  o.px_per_mm = 3.0;
  o.colouring = Colouring::kModelDistance;
  const Rendering r = render_scan(scene.cloud, drawing, o);
  keep(r.image, "ellipsoid_fixed_camera");

  for (const Panel* panel : {&r.sensor, &r.top}) {
    SCOPED_TRACE(panel->title);
    const Eigen::Vector2d c(panel->x0 + 200.0, 200.0);
    // The silhouette from above is the equator: an ellipse of 40 x 25 mm, 120 x 75 px.
    for (const double w : {0.3, 1.2, 2.0, 2.8, 3.6, 4.4, 5.2, 6.0}) {
      const Eigen::Vector2d edge = c + Eigen::Vector2d(120.0 * std::cos(w), -75.0 * std::sin(w));
      EXPECT_TRUE(colour_near(r.image, edge, kModelColour)) << "angle " << w;
    }
    // Between the wireframe lines the part's own points show, green (on the model); the table
    // beside it is far from the part and grey.
    const Eigen::Vector2d on_part =
        c + Eigen::Vector2d(60.0 * std::cos(0.26), -37.5 * std::sin(0.26));
    const Rgb part_colour = pixel(r.image, on_part);
    EXPECT_GT(part_colour.g, 150) << int(part_colour.r) << " " << int(part_colour.b);
    EXPECT_LT(part_colour.r, 120);
    EXPECT_EQ(pixel(r.image, c + Eigen::Vector2d(0.0, 120.0)), kFarColour);
  }
}

TEST(Render, ModelWithoutScanLeavesTheRestBackground) {
  Drawing drawing;
  Superquadric sphere;
  sphere.a1 = sphere.a2 = sphere.a3 = 10.0;
  drawing.parts.push_back({"sphere", sphere, Eigen::Isometry3d::Identity()});
  RenderOptions o;
  o.panel_width = o.panel_height = 200;
  o.toward_sensor = Eigen::Vector3d::UnitZ();
  o.px_per_mm = 5.0;
  const Rendering r = render_scan(PointCloud{}, drawing, o);
  const Eigen::Vector2d c(100.0, 100.0);
  EXPECT_TRUE(colour_near(r.image, c + Eigen::Vector2d(50.0 * std::cos(0.4), 50.0 * std::sin(0.4)),
                          kModelColour));
  // Outside the sphere and between its lines: nothing drawn.
  EXPECT_EQ(pixel(r.image, c + Eigen::Vector2d(60.0 * std::cos(0.4), 60.0 * std::sin(0.4))),
            kBackground);
  EXPECT_EQ(pixel(r.image, c + Eigen::Vector2d(-70.0, 45.0)), kBackground);
}

TEST(Render, EntrancePlaneOfASlantedBoreFromTheScan) {
  sim::SyntheticBoreOptions o;
  o.radius = 5.0;
  o.slant_deg = 30.0;
  o.spacing = 0.3;
  const sim::SyntheticBoreScan scan = sim::make_synthetic_bore(o);
  const DrawnBore bore{scan.truth.entrance, scan.truth.axis, 5.0, Eigen::Vector3d::Zero(), 0.0};
  const Eigen::Vector3d n = entrance_plane_normal(bore, scan.cloud.points);
  EXPECT_GT(n.dot(scan.truth.plane_normal), std::cos(2.0 * kPi / 180.0));
  // The wall is as deep as the scan shows it, not the drawing's default of two radii.
  EXPECT_GT(bore_depth(bore, scan.cloud.points), 2.5 * o.radius);
}

TEST(Render, WritesAPngFile) {
  const sim::SyntheticBoreScan scan = clean_bore();
  BoreResult result;
  result.found = true;
  result.entrance = scan.truth.entrance;
  result.axis = scan.truth.axis;
  result.radius = scan.truth.radius;
  const Drawing drawing = bore_drawing(result);
  EXPECT_EQ(drawing.bores.size(), 1u);
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "rangefit_render_test.png";
  std::string error;
  ASSERT_TRUE(write_detection_png(path.string(), scan.cloud, drawing, {}, &error)) << error;
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
  std::filesystem::remove(path);
  EXPECT_FALSE(write_detection_png("/nonexistent-dir/x.png", scan.cloud, drawing, {}, &error));
  EXPECT_NE(error.find("/nonexistent-dir/x.png"), std::string::npos);
}

// The font caches go before exit, so LeakSanitizer sees only our own allocations.
class FontCaches : public ::testing::Environment {
 public:
  void TearDown() override { release_font_caches(); }
};
const auto* const kFontCaches = ::testing::AddGlobalTestEnvironment(new FontCaches);

}  // namespace
}  // namespace rangefit::render
