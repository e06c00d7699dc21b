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
#include "sim/stripe_scan.hpp"
#include "sim/stripe_sweep.hpp"
#include "sim/superquadric_raycast.hpp"
#include "test/render/picture_checks.hpp"

namespace rangefit::render {
namespace render_test {

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
  drawing.bores.push_back({t.entrance, t.axis, t.radius, t.plane_normal, 6.0 * t.radius, {}});
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

// A sphere on the table scanned by the stripe cell (laser from above, camera 45 degrees off to
// +y): with no view given, the first panel looks from the sensor the cloud says took it, and the
// model's outline and the scanned cap sit where that view puts them.
TEST(Render, AStripeScanIsDrawnFromItsOwnSensor) {
  sim::ScenePart sphere;
  sphere.name = "sphere";
  sphere.model.a1 = sphere.model.a2 = sphere.model.a3 = 30.0;
  const Eigen::Vector3d c(10.0, -5.0, 30.0);
  sphere.T_world_part.translation() = c;
  sim::ScanSetup setup;
  setup.step_mm = 1.0;
  setup.max_points = 40000;
  setup.noise_mm = 0.0;
  const Eigen::AlignedBox3d cover(Eigen::Vector3d(-45, -50, 0), Eigen::Vector3d(65, 40, 65));
  const sim::StripeSweep sweep = sim::make_sweep(setup, cover);
  sim::StripeScan scan = sim::scan_stripe(sim::PartCaster({sphere}), sweep, {}, 1);
  scan.cloud.sensor = sweep.view();  // as the cell's scan loop records it
  ASSERT_GT(scan.cloud.size(), 5000u);

  Drawing drawing;
  drawing.parts.push_back({sphere.name, sphere.model, sphere.T_world_part});
  RenderOptions o;
  o.panel_width = o.panel_height = 400;
  o.look_at = c;
  o.px_per_mm = 4.0;
  o.colouring = Colouring::kModelDistance;
  const Rendering r = render_scan(scan.cloud, drawing, o);
  keep(r.image, "sphere_stripe_sensor_view");

  // From between the laser apex and the camera of the profile through the sphere's centre.
  const sim::ProfilePose pose = sweep.pose(sweep.position_of(c));
  const Eigen::Vector3d toward =
      ((pose.apex - c).normalized() + (pose.camera - c).normalized()).normalized();
  EXPECT_TRUE(r.sensor.title.starts_with("sensor view")) << r.sensor.title;
  // (It looks at the middle of the wireframe, within a hair of the centre.)
  EXPECT_NEAR((r.sensor.view.toward - toward).norm(), 0.0, 1e-3) << r.sensor.view.toward;
  // Not the default oblique view (from -y): the camera is on +y.
  EXPECT_GT(r.sensor.view.toward.y(), 0.2);

  const Panel& p = r.sensor;
  const OrthoView& v = p.view;
  // The wireframe's lines on the side facing the sensor are drawn where this view projects
  // them (but where the part's axes, drawn over them, cross or run along them).
  const std::vector<Polyline> wireframe = part_wireframe(drawing.parts.front());
  const auto under_an_axis = [&](const Eigen::Vector2d& q) {
    for (const Polyline& axis : wireframe) {
      if (axis.role == LineRole::kModel) continue;
      for (std::size_t k = 1; k < axis.points.size(); ++k) {
        const Eigen::Vector2d a = p.pixel(axis.points[k - 1]), b = p.pixel(axis.points[k]);
        const double t = std::clamp((q - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
        if ((a + t * (b - a) - q).norm() < 4.0) return true;
      }
    }
    return false;
  };
  int checked = 0, drawn = 0;
  for (const Polyline& line : wireframe) {
    if (line.role != LineRole::kModel) continue;
    for (std::size_t k = 0; k < line.points.size(); k += 3) {
      const Eigen::Vector2d q = p.pixel(line.points[k]);
      if (line.normals[k].dot(v.toward) < 0.5 || under_an_axis(q)) continue;
      ++checked;
      drawn += colour_near(r.image, q, kModelColour);
    }
  }
  EXPECT_GT(checked, 40);
  EXPECT_EQ(drawn, checked);
  // The silhouette is a circle of 30 mm = 120 px around the centre, seen from any side: the
  // scanned cap fills it (green, on the model) and the table shows beside it (grey, far from
  // the model).
  const Eigen::Vector2d centre = p.pixel(c);
  EXPECT_NEAR((centre - Eigen::Vector2d(200.0, 200.0)).norm(), 0.0, 1e-9);
  // (Most of a 7 x 7 patch: wireframe lines cross the cap; its lower rim, which the camera
  // sees at a grazing angle, is sparse.)
  const auto green_share = [&](const Eigen::Vector2d& q) {
    int green = 0;
    for (int dy = -3; dy <= 3; ++dy) {
      for (int dx = -3; dx <= 3; ++dx) {
        const Rgb px = pixel(r.image, q + Eigen::Vector2d(dx, dy));
        green += px.g > 150 && px.r < 120;
      }
    }
    return green / 49.0;
  };
  for (const double w : {0.4, 2.5, 3.5, 4.3, 5.0, 6.0}) {  // the upper half, away from the rim
    const Eigen::Vector2d inside =
        centre + 0.6 * 120.0 * Eigen::Vector2d(std::cos(w), -std::abs(std::sin(w)));
    EXPECT_GT(green_share(inside), 0.6) << "angle " << w;
  }
  for (const double side : {-1.0, 1.0}) {  // the table to the left and right of the sphere
    const Eigen::Vector2d beside = centre + Eigen::Vector2d(side * 1.3 * 120.0, -12.0);
    EXPECT_EQ(pixel(r.image, beside), kFarColour) << "side " << side;
    EXPECT_NE(pixel(r.image, centre + Eigen::Vector2d(side * 1.12 * 120.0, -12.0)), kModelColour);
  }
}

// A countersink (Ø12 x 90 deg into Ø6) and a 10 x 8 mm ellipse, on a tilted axis, as fitted.
struct ShapedBore {
  DrawnBore drawn;
  BoreSurface fitted;  // the same wall as detect/ describes it
};

ShapedBore shaped_bore(bool cone) {
  ShapedBore b;
  const Eigen::Vector3d axis = Eigen::Vector3d(0.1, -0.2, 1.0).normalized();
  const Eigen::Vector3d major = axis.cross(Eigen::Vector3d(1.0, 1.0, 0.0)).normalized();
  BoreShape shape;
  shape.cone = cone;
  if (cone) {
    shape.half_angle = kPi / 4.0;
    shape.cylinder_radius = 3.0;
  } else {
    shape.radius2 = 4.0;
    shape.major_axis = major;
  }
  const double radius = cone ? 6.0 : 5.0;
  b.drawn = {Eigen::Vector3d(10.0, -5.0, 2.0), axis, radius, axis, 8.0, shape};
  b.fitted.cone = cone;
  b.fitted.entrance = b.drawn.entrance;
  b.fitted.axis = axis;
  b.fitted.major = major;
  b.fitted.radius = radius;
  b.fitted.radius2 = shape.radius2;
  b.fitted.half_angle = shape.half_angle;
  b.fitted.cylinder_radius = shape.cylinder_radius;
  return b;
}

// The wireframe lies on the fitted cone or ellipse (not on a cylinder of the entrance radius),
// the picture along the axis shows the countersink's cylinder and the ellipse's minor extent,
// and points on the fitted wall are at distance 0 from the model.
TEST(Render, ConeAndEllipseBoresAreDrawnAsFittedNotAsCylinders) {
  for (const bool cone : {true, false}) {
    SCOPED_TRACE(cone ? "countersink" : "ellipse");
    const ShapedBore b = shaped_bore(cone);
    int checked = 0, off_cylinder = 0;
    for (const Polyline& line : bore_wireframe(b.drawn, b.drawn.depth)) {
      if (line.role != LineRole::kModel) continue;
      for (const Eigen::Vector3d& p : line.points) {
        ++checked;
        EXPECT_NEAR(surface_residual(b.fitted, p), 0.0, 1e-9);
        const Eigen::Vector3d d = p - b.drawn.entrance;
        off_cylinder +=
            std::abs((d - d.dot(b.fitted.axis) * b.fitted.axis).norm() - b.drawn.radius) > 0.5;
      }
    }
    EXPECT_GT(checked, 200);
    EXPECT_GT(off_cylinder, checked / 4);

    Drawing drawing;
    drawing.bores.push_back(b.drawn);
    RenderOptions o;
    o.panel_width = o.panel_height = 400;
    o.toward_sensor = b.fitted.axis;
    o.look_at = b.drawn.entrance;
    o.px_per_mm = 10.0;
    const Rendering r = render_scan(PointCloud{}, drawing, o);
    keep(r.image, cone ? "countersink_along_axis" : "ellipse_along_axis");
    const Eigen::Vector3d minor = b.fitted.axis.cross(b.fitted.major);
    for (const double w : {1.3, 1.85, 4.45, 5.0}) {  // between the generators, off the major axis
      const Eigen::Vector3d dir = std::cos(w) * b.fitted.major + std::sin(w) * minor;
      // Countersink: its cylinder's ring (nothing of an entrance-radius cylinder is there);
      // ellipse: its outline, and nothing where a circle of the entrance radius would be.
      const double on = cone ? 3.0 : 5.0 * 4.0 / std::hypot(4.0 * std::cos(w), 5.0 * std::sin(w));
      const Eigen::Vector3d wall = b.drawn.entrance - 6.0 * b.fitted.axis + on * dir;
      EXPECT_TRUE(colour_near(r.image, r.sensor.pixel(wall), kModelColour)) << "angle " << w;
      if (!cone) {
        EXPECT_EQ(pixel(r.image, r.sensor.pixel(b.drawn.entrance + 5.0 * dir)), kBackground)
            << "angle " << w;
      }
      EXPECT_NEAR(model_distance(drawing, wall), 0.0, 1e-9) << "angle " << w;
    }
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
  const DrawnBore bore{scan.truth.entrance, scan.truth.axis, 5.0, Eigen::Vector3d::Zero(), 0.0, {}};
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

}  // namespace render_test
}  // namespace rangefit::render
