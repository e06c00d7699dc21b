// A cone or elliptic bore's model reaches detect/ the same way from `rangefit bore` and from a
// JSON or DDS request (the one adapter, daemon/service/detection_adapter), round-trips the JSON
// of HTTP/TCP and the spool and the DDS request (metres), means "a cylinder" in an older request,
// and comes back as the result's shape in the CLI's JSON.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>

#include "daemon/dds/messages.hpp"
#include "daemon/service/detection_adapter.hpp"
#include "daemon/service/json_codec.hpp"
#include "daemon/service/request_validation.hpp"
#include "io/cloud_io.hpp"
#include "test/daemon/cli_run.hpp"
#include "test/detect/bore_test_cases.hpp"

namespace rangefit::daemon {
namespace bore_shape_request_test {

DaemonConfig css_only() {
  DaemonConfig config;
  DeviceConfig css;
  css.name = css.kind = "css";
  config.devices = {css};
  config.service.bore_sensor = "css";
  return config;
}

ScanRequest countersink_request() {
  ScanRequest req;
  req.id = "countersink-1";
  req.kind = DetectKind::kBore;
  req.bore.radius_mm = 6.0;
  req.bore.half_angle_rad = std::numbers::pi / 4;
  req.bore.cylinder_radius_mm = 3.0;
  return req;
}

TEST(BoreShapeRequest, ConeAndEllipseFieldsRoundTripTheJsonAndReachThePrior) {
  ScanRequest req = countersink_request();
  ScanRequest back;
  std::string error;
  ASSERT_TRUE(from_json(to_json(req), back, &error)) << error;
  EXPECT_EQ(back.bore.half_angle_rad, req.bore.half_angle_rad);
  EXPECT_EQ(back.bore.cylinder_radius_mm, 3.0);
  EXPECT_FALSE(back.bore.major_axis);
  const BoreDetection cone = bore_detection(bore_query(back, 1), ScanSensor{});
  EXPECT_EQ(cone.prior.half_angle, req.bore.half_angle_rad);
  EXPECT_EQ(cone.prior.cylinder_radius, 3.0);
  EXPECT_EQ(cone.prior.radius2, 0.0);

  req = ScanRequest{};
  req.id = "ellipse-1";
  req.kind = DetectKind::kBore;
  req.bore.radius_mm = 5.0;
  req.bore.radius2_mm = 4.5;
  req.bore.major_axis = Eigen::Vector3d(1, 2, 0);
  ASSERT_TRUE(from_json(to_json(req), back, &error)) << error;
  EXPECT_EQ(validate_request(back, css_only()), "");
  const BoreDetection ellipse = bore_detection(bore_query(back, 1), ScanSensor{});
  EXPECT_EQ(ellipse.prior.radius2, 4.5);
  EXPECT_EQ(ellipse.prior.major_axis, Eigen::Vector3d(1, 2, 0));
}

TEST(BoreShapeRequest, ConeAndEllipseFieldsRoundTripTheDdsRequestInMetres) {
  ScanRequest req = countersink_request();
  req.bore.radius2_mm = 4.5;
  req.bore.major_axis = Eigen::Vector3d(0, 1, 0);
  const RequestOut out(req, false);
  EXPECT_DOUBLE_EQ(out.msg().bore_cylinder_radius, 0.003);  // metres on the wire
  EXPECT_DOUBLE_EQ(out.msg().bore_radius2, 0.0045);
  std::string error;
  const ScanRequest back = from_msg(out.msg(), &error);
  EXPECT_EQ(error, "");
  EXPECT_EQ(back.bore.half_angle_rad, req.bore.half_angle_rad);
  EXPECT_NEAR(back.bore.cylinder_radius_mm, 3.0, 1e-12);
  EXPECT_NEAR(back.bore.radius2_mm, 4.5, 1e-12);
  ASSERT_TRUE(back.bore.major_axis);
  EXPECT_EQ(*back.bore.major_axis, Eigen::Vector3d(0, 1, 0));
  // An older client's request has the new fields zero: a circular cylinder.
  ScanRequest old;
  old.kind = DetectKind::kBore;
  old.bore.radius_mm = 5.0;
  const ScanRequest plain = from_msg(RequestOut(old, false).msg(), &error);
  EXPECT_EQ(plain.bore.half_angle_rad, 0.0);
  EXPECT_EQ(plain.bore.radius2_mm, 0.0);
  EXPECT_FALSE(plain.bore.major_axis);
}

TEST(BoreShapeRequest, AnOlderRequestIsACylinder) {
  nlohmann::json j = to_json(ScanRequest{});
  j["bore"].erase("half_angle_rad");
  ScanRequest back;
  std::string error;
  ASSERT_TRUE(from_json(j, back, &error)) << error;
  EXPECT_EQ(back.bore.half_angle_rad, 0.0);
  EXPECT_EQ(back.bore.radius2_mm, 0.0);
  EXPECT_FALSE(back.bore.major_axis);
}

TEST(BoreShapeRequest, ValidationNamesTheShapeFieldThatIsWrong) {
  ScanRequest req = countersink_request();
  req.bore.half_angle_rad = 2.0;
  EXPECT_NE(validate_request(req, css_only()).find("half_angle_rad"), std::string::npos);
  req = countersink_request();
  req.bore.half_angle_rad = 0.0;
  req.bore.radius2_mm = 4.0;  // no major axis
  EXPECT_NE(validate_request(req, css_only()).find("major_axis"), std::string::npos);
  req.bore.major_axis = Eigen::Vector3d::UnitX();
  req.bore.cylinder_radius_mm = 0.0;
  EXPECT_EQ(validate_request(req, css_only()), "");
}

#ifdef RANGEFIT_CLI_PATH
using test::CliRun;
using test::run_cli;

std::string xyz(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s.precision(17);
  s << v.x() << "," << v.y() << "," << v.z();
  return s.str();
}

TEST(BoreShapeRequest, CliFitsACountersinkAndPrintsItsShapeAsJson) {
  const auto scan =
      sim::make_synthetic_bore(test::shape_scan_options(test::ShapeKind::kCountersink, 1));
  const rangefit::BorePrior p = test::shape_prior(scan.truth, 1);
  const auto path = std::filesystem::temp_directory_path() /
                    ("rangefit_countersink_" + std::to_string(::getpid()) + ".ply");
  io::write_cloud(path, scan.cloud, io::Precision::kFloat64);
  const std::string args = "bore --cloud " + path.string() + " --cad-entrance " + xyz(p.entrance) +
                           " --cad-axis " + xyz(p.axis) + " --cad-plane-normal " +
                           xyz(*p.plane_normal) + " --view-dir " + xyz(scan.truth.view_dir) +
                           " --cad-radius 6 ";
  const CliRun r =
      run_cli(args + "--cad-half-angle 0.7853981633974483 --cad-cylinder-radius 3 --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j.at("model"), "cone");
  EXPECT_NEAR(j.at("half_angle").get<double>(), std::numbers::pi / 4, 0.2 * std::numbers::pi / 180);
  EXPECT_NEAR(j.at("cylinder_radius").get<double>(), 3.0, 0.05);
  EXPECT_GT(j.at("sigma").at("half_angle_rad").get<double>(), 0.0);
  const CliRun no_axis = run_cli(args + "--cad-radius2 5");
  EXPECT_EQ(no_axis.exit_code, 1) << no_axis.output;
  EXPECT_NE(no_axis.output.find("--cad-major-axis"), std::string::npos);
  std::filesystem::remove(path);
}
#endif

}  // namespace bore_shape_request_test
}  // namespace rangefit::daemon
