// The service's picture of a result (daemon/result_picture.hpp): what it draws from a spooled
// result, the picture.png of every spool entry, and `rangefit replay --png`.
#include "daemon/service/result_picture.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "daemon/service/bore_shape_json.hpp"
#include "daemon/service/object_result_json.hpp"
#include "daemon/service/spool.hpp"
#include "render/render.hpp"
#include "test/render/picture_checks.hpp"

namespace rangefit::daemon {
namespace result_picture_test {
namespace fs = std::filesystem;

// White (the model's colour, each channel above 225) within a pixel of p.
bool white_near(const render::Image& image, const Eigen::Vector2d& p) {
  return render::test::colour_near(image, p, render::kModelColour, 1, 29);
}

bool is_png(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  in.read(magic, 4);
  return in && std::string(magic + 1, 3) == "PNG";
}

// What the service reports for the bore: the entrance and the axis as a part pose.
DetectionResult bore_result(const sim::SyntheticBoreTruth& t) {
  DetectionResult r;
  r.request_id = "bore-1";
  r.kind = DetectKind::kBore;
  r.found = true;
  r.bore_radius_mm = t.radius;
  PartPose p;
  p.name = "bore";
  p.T_world_part.linear() =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), t.axis).toRotationMatrix();
  p.T_world_part.translation() = t.entrance;
  p.score = 1.0;
  r.parts.push_back(p);
  return r;
}

TEST(ResultPicture, ASpooledBoreResultIsDrawnOnTheHoleEdge) {
  const sim::SyntheticBoreScan scan = render::test::clean_bore();
  const render::Drawing d = result_drawing(bore_result(scan.truth), nullptr);
  ASSERT_EQ(d.bores.size(), 1u);
  render::RenderOptions o;
  o.panel_width = o.panel_height = 400;
  o.toward_sensor = scan.truth.axis;
  o.look_at = scan.truth.entrance;
  o.px_per_mm = 10.0;
  const render::Rendering r = render::render_scan(scan.cloud, d, o);
  for (int k = 0; k < 12; ++k) {
    const double w = 2.0 * std::numbers::pi * (k + 0.5) / 12.0;
    const Eigen::Vector2d on_ring =
        Eigen::Vector2d(200, 200) + 50.0 * Eigen::Vector2d(std::cos(w), std::sin(w));
    EXPECT_TRUE(white_near(r.image, on_ring)) << "angle " << w;
  }
  EXPECT_FALSE(white_near(r.image, Eigen::Vector2d(200 + 80, 200 + 10)));  // the plate
  render::release_font_caches();
}

// The shape's standard errors come back as written, keys with their units, and a result written
// before the keys carried units ("radius", "half_angle", ...) reads the same.
TEST(ResultPicture, ShapeStandardErrorsReadBackUnderTheirUnitsAndTheOldKeys) {
  BoreShape shape;
  shape.cone = true;
  shape.half_angle = 0.7;
  shape.cylinder_radius = 3.0;
  shape.sigma_radius = 0.01;
  shape.sigma_entrance = 0.02;
  shape.sigma_axis = 0.003;
  shape.sigma_half_angle = 0.004;
  shape.sigma_cylinder_radius = 0.05;
  nlohmann::json j = bore_shape_json(shape);
  EXPECT_EQ(j.at("sigma").at("half_angle_rad"), 0.004);
  EXPECT_EQ(j.at("sigma").at("cylinder_radius_mm"), 0.05);
  const auto check = [&](const nlohmann::json& written) {
    const std::optional<BoreShape> back = bore_shape_from_json(written);
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(back->sigma_radius, 0.01);
    EXPECT_EQ(back->sigma_entrance, 0.02);
    EXPECT_EQ(back->sigma_axis, 0.003);
    EXPECT_EQ(back->sigma_half_angle, 0.004);
    EXPECT_EQ(back->sigma_cylinder_radius, 0.05);
  };
  check(j);
  j["sigma"] = {{"radius", 0.01},
                {"entrance", 0.02},
                {"axis", 0.003},
                {"half_angle", 0.004},
                {"cylinder_radius", 0.05}};
  check(j);
}

// A countersink's result (details.shape as the service writes it, bore_shape_json): drawn as
// its cone into its cylinder, seen along the axis the cylinder's ring at 3 mm = 30 px, where a
// cylinder of the entrance radius (6 mm) draws nothing; a shape no fit gives is refused.
TEST(ResultPicture, ASpooledCountersinkIsDrawnAsItsConeAndCylinder) {
  const sim::SyntheticBoreScan scan = render::test::clean_bore();
  DetectionResult r = bore_result(scan.truth);
  r.bore_radius_mm = 6.0;
  BoreShape shape;
  shape.cone = true;
  shape.half_angle = std::numbers::pi / 4.0;
  shape.cylinder_radius = 3.0;
  r.details["shape"] = bore_shape_json(shape);
  const render::Drawing d = result_drawing(r, nullptr);
  ASSERT_EQ(d.bores.size(), 1u);
  ASSERT_TRUE(d.bores[0].shape.has_value());
  EXPECT_TRUE(d.bores[0].shape->cone);
  EXPECT_DOUBLE_EQ(d.bores[0].shape->half_angle, shape.half_angle);
  EXPECT_DOUBLE_EQ(d.bores[0].shape->cylinder_radius, 3.0);
  render::RenderOptions o;
  o.panel_width = o.panel_height = 400;
  o.toward_sensor = scan.truth.axis;
  o.look_at = scan.truth.entrance;
  o.px_per_mm = 10.0;
  const render::Rendering picture = render::render_scan(PointCloud{}, d, o);
  for (const double w : {0.26, 1.83, 3.4, 4.97}) {  // between the generators (every 30 deg)
    EXPECT_TRUE(white_near(picture.image, Eigen::Vector2d(200, 200) +
                                              30.0 * Eigen::Vector2d(std::cos(w), std::sin(w))))
        << "angle " << w;
  }
  render::release_font_caches();

  r.details["shape"]["half_angle"] = 2.0;  // 115 deg
  std::string error;
  EXPECT_FALSE(write_result_picture(fs::temp_directory_path() / "rangefit_bad_shape.png",
                                    scan.cloud, r, nullptr, &error));
  EXPECT_NE(error.find("half_angle"), std::string::npos) << error;
  r.details["shape"] = {{"model", "sphere"}};
  EXPECT_THROW(result_drawing(r, nullptr), std::invalid_argument);
}

TEST(ResultPicture, ObjectPartsNeedTheirModel) {
  DetectionResult r;
  r.kind = DetectKind::kObject;
  r.found = true;
  r.parts.push_back({"head", Eigen::Isometry3d::Identity(), 1.0, 0});
  std::string error;
  EXPECT_FALSE(write_result_picture(fs::temp_directory_path() / "rangefit_no_model.png",
                                    PointCloud{}, r, nullptr, &error));
  EXPECT_NE(error.find("model"), std::string::npos) << error;
  ObjectModel other{"mallet", {{"shaft", Superquadric{}}}, {}};
  EXPECT_THROW(result_drawing(r, &other), std::invalid_argument);
}

// The service's picture of an object result prints each part's scores from the result's
// details, in the line `rangefit object --png` prints for the same detection; details that are
// not what the service writes leave the line out and throw nothing.
TEST(ResultPicture, AnObjectPartsScoresComeFromTheDetailsAsTheCliPrintsThem) {
  const ObjectModel model{
      "mallet",
      {{"head", Superquadric{20, 20, 30, 0.1, 1.0}}, {"shaft", Superquadric{6, 6, 70, 0.1, 1.0}}},
      {}};
  ObjectDetectResult found;
  DetectedInstance inst;
  for (const char* name : {"head", "shaft"}) {
    DetectedPart part;
    part.name = name;
    part.T_world_part.translation() = Eigen::Vector3d(10, 20, 30);
    part.scores.measure = name[0] == 'h' ? 0.0412 : 0.0733;
    part.scores.interior = 3;
    part.scores.surface = name[0] == 'h' ? 812 : 451;
    part.scores.coverage = 0.87;
    part.scores.seen_through = 0.01;
    inst.parts.push_back(part);
  }
  found.instances.push_back(inst);
  DetectionResult r;
  r.kind = DetectKind::kObject;
  r.found = true;
  for (const DetectedPart& part : inst.parts)
    r.parts.push_back({part.name, part.T_world_part, 1.0, 0});
  r.details = object_result_json(model, found);

  const std::vector<std::string> cli = render::object_drawing(model, found).legend;
  const std::vector<std::string> service = result_drawing(r, &model).legend;
  for (const DetectedPart& part : inst.parts) {
    const std::string line = render::scores_line(part.scores);
    EXPECT_NE(std::find(cli.begin(), cli.end(), line), cli.end()) << line;
    EXPECT_NE(std::find(service.begin(), service.end(), line), service.end()) << line;
  }

  for (const nlohmann::json& bad :
       {nlohmann::json("instances"), nlohmann::json{{"instances", 7}},
        nlohmann::json{{"instances", {{{"parts", {{{"name", 3}}}}}}}},
        nlohmann::json{
            {"instances", {{{"parts", {{{"name", "head"}, {"scores", {{"M", "x"}}}}}}}}}}}) {
    r.details = bad;
    EXPECT_NO_THROW(result_drawing(r, &model)) << bad.dump();
  }
}

class SpoolPictures : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("rangefit_spool_pictures_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A spool entry of the synthetic bore scan, as the service writes it.
  fs::path spool_entry(bool pictures) {
    SpoolConfig c;
    c.directory = dir_ / "spool";
    c.pictures = pictures;
    Spool spool(c);
    std::string why;
    EXPECT_TRUE(spool.open(&why)) << why;
    spool.set_picture([](const fs::path& path, const PointCloud& cloud,
                         const DetectionResult& result, std::string* error) {
      return write_result_picture(path, cloud, result, nullptr, error);
    });
    const sim::SyntheticBoreScan scan = render::test::clean_bore();
    ScanRequest request;
    request.id = "bore-1";
    request.bore.position_mm = scan.truth.entrance + Eigen::Vector3d(0.5, -0.3, 0.0);
    request.bore.axis = scan.truth.axis;
    request.bore.radius_mm = 5.0;
    DetectionResult result = bore_result(scan.truth);
    EXPECT_TRUE(spool.write(request, scan.cloud, result, &why)) << why;
    return result.spool_entry;
  }

  fs::path dir_;
};

TEST_F(SpoolPictures, EveryEntryWithAScanHasItsPictureUnlessTurnedOff) {
  EXPECT_TRUE(is_png(spool_entry(true) / "picture.png"));
  EXPECT_FALSE(fs::exists(spool_entry(false) / "picture.png"));
}

#ifdef RANGEFIT_CLI_PATH
TEST_F(SpoolPictures, ReplayDrawsTheReplayedDetection) {
  const fs::path entry = spool_entry(false);
  const fs::path png = dir_ / "replay.png";
  const std::string command = std::string(RANGEFIT_CLI_PATH) + " replay " + entry.string() +
                              " --png " + png.string() + " > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_TRUE(is_png(png));
  // An unwritable picture is a bad-input exit, not a crash.
  const std::string bad = std::string(RANGEFIT_CLI_PATH) + " replay " + entry.string() +
                          " --png /nonexistent/dir/x.png > /dev/null 2>&1";
  EXPECT_EQ(WEXITSTATUS(std::system(bad.c_str())), 1);
}
#endif

}  // namespace result_picture_test
}  // namespace rangefit::daemon
