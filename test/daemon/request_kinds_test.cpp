// The request fields that reach what `rangefit bore|learn|calibrate` take (a pipe's walls, the
// sensor the user knows, the parts to learn, the calibration body) survive the DDS wire in
// metres and the JSON of HTTP/TCP and the spool in mm, with the same names and defaults; an older
// client's request means what it meant; validation names the field that is wrong.
#include <gtest/gtest.h>

#include <numbers>

#include "daemon/dds/messages.hpp"
#include "daemon/dds/service_body.hpp"
#include "daemon/dds/service_request.hpp"
#include "daemon/service/json_codec.hpp"
#include "daemon/service/request_validation.hpp"

namespace rangefit::daemon {
namespace request_kinds_test {

ScanRequest pipe_request() {
  ScanRequest req;
  req.id = "pipe-1";
  req.kind = DetectKind::kBore;
  req.bore.radius_mm = 6.0;
  req.bore.outer_radius_mm = 8.0;
  req.bore.walls = "both";
  req.bore.normal_keep = 0.25;
  req.view_dir = Eigen::Vector3d(0.0, -0.48, 0.877);
  req.sensor_position = Eigen::Vector3d(10.0, -150.0, 520.0);
  return req;
}

ScanRequest calibrate_request() {
  ScanRequest req;
  req.id = "cal-1";
  req.kind = DetectKind::kCalibrate;
  req.target.kind = "stripe";
  req.target.edge_mm = 150.0;
  req.target.bar_mm = 15.0;
  req.target.T_table_target.linear() =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  req.target.T_table_target.translation() = Eigen::Vector3d(5.0, 3.0, 130.0);
  return req;
}

// One robot pose of a css calibration that joins two earlier poses' requests.
ScanRequest css_calibrate_request() {
  ScanRequest req;
  req.id = "css-3";
  req.kind = DetectKind::kCalibrate;
  req.target.kind = "css";
  req.target.radius_mm = 12.7;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.8, Eigen::Vector3d(-1, 2, 0.5).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(450.0, -120.0, 610.0);
  req.target.T_base_joint = T;
  req.target.scans = {"css-1", "css-2"};
  return req;
}

// One tilt's pan sweep of a pantilt calibration that joins an earlier tilt's request.
ScanRequest pantilt_calibrate_request() {
  ScanRequest req;
  req.id = "sweep-2";
  req.kind = DetectKind::kCalibrate;
  req.target.kind = "pantilt";
  req.target.edge_mm = 100.0;
  req.target.bar_mm = 10.0;
  req.target.T_table_target.linear() =
      Eigen::AngleAxisd(0.6, Eigen::Vector3d(0.2, -0.4, 1).normalized()).toRotationMatrix();
  req.target.T_table_target.translation() = Eigen::Vector3d(900.0, -40.0, 250.0);
  req.target.tilt_rad = 0.35;
  req.target.scans = {"sweep-1"};
  return req;
}

DaemonConfig css_and_stripe() {
  DaemonConfig config;
  DeviceConfig css, stripe;
  css.name = css.kind = "css";
  stripe.name = stripe.kind = "stripe";
  config.devices = {css, stripe};
  config.service.bore_sensor = "css";
  config.service.object_sensor = "stripe";
  return config;
}

void expect_same_pipe(const ScanRequest& back, const ScanRequest& req) {
  EXPECT_NEAR(back.bore.outer_radius_mm, 8.0, 1e-12);
  EXPECT_EQ(back.bore.walls, "both");
  EXPECT_EQ(back.bore.normal_keep, 0.25);
  ASSERT_TRUE(back.view_dir);
  EXPECT_EQ(*back.view_dir, *req.view_dir);
  ASSERT_TRUE(back.sensor_position);
  EXPECT_LT((*back.sensor_position - *req.sensor_position).norm(), 1e-9);
}

TEST(RequestKinds, PipeWallsAndSensorKnowledgeRoundTripTheWireAndJson) {
  const ScanRequest req = pipe_request();
  const RequestOut out(req, false);
  std::string error;
  const ScanRequest wire = from_msg(out.msg(), &error);
  EXPECT_EQ(error, "");
  expect_same_pipe(wire, req);
  ScanRequest json;
  ASSERT_TRUE(from_json(to_json(req), json, &error)) << error;
  expect_same_pipe(json, req);
}

TEST(RequestKinds, LearnAndCalibrateRoundTripTheWireAndJson) {
  ScanRequest learn;
  learn.id = "learn-1";
  learn.kind = DetectKind::kLearn;
  learn.model = "mallet";
  learn.parts = 2;
  std::string error;
  const RequestOut learn_out(learn, true);
  const ScanRequest learn_back = from_msg(learn_out.msg(), &error);
  EXPECT_EQ(error, "");
  EXPECT_EQ(learn_back.kind, DetectKind::kLearn);
  EXPECT_EQ(learn_back.parts, 2);
  EXPECT_EQ(learn_back.model, "mallet");
  EXPECT_TRUE(learn_back.sensors.empty());
  // Several sensors' scans fused: the list crosses the wire and JSON in order.
  learn.sensors = {"stripe", "head"};
  const RequestOut views_out(learn, true);
  EXPECT_EQ(from_msg(views_out.msg(), &error).sensors, learn.sensors);
  EXPECT_EQ(error, "");
  ScanRequest views_json;
  ASSERT_TRUE(from_json(to_json(learn), views_json, &error)) << error;
  EXPECT_EQ(views_json.sensors, learn.sensors);

  const ScanRequest cal = calibrate_request();
  const RequestOut cal_out(cal, true);
  for (const ScanRequest& back : {from_msg(cal_out.msg(), &error), [&] {
                                    ScanRequest j;
                                    EXPECT_TRUE(from_json(to_json(cal), j, &error)) << error;
                                    return j;
                                  }()}) {
    EXPECT_EQ(back.kind, DetectKind::kCalibrate);
    EXPECT_EQ(back.target.kind, "stripe");
    EXPECT_NEAR(back.target.edge_mm, 150.0, 1e-9);
    EXPECT_NEAR(back.target.bar_mm, 15.0, 1e-9);
    EXPECT_TRUE(back.target.T_table_target.isApprox(cal.target.T_table_target, 1e-9));
  }
}

// The request back from its topic message, the same fields as a /rangefit/detect service call
// (sequence number seq), and JSON; each decodes without an error.
std::vector<ScanRequest> decoded_three_ways(const ScanRequest& req, const RequestOut& out,
                                            std::int64_t seq) {
  std::string topic_error, service_error, json_error;
  std::vector<ScanRequest> back;
  back.push_back(from_msg(out.msg(), &topic_error));
  const auto call = service_sample<rangefit_msgs_srv_dds__Detect_Request_>(7, seq, out.msg());
  back.push_back(from_service_request(call, &service_error));
  back.emplace_back();
  EXPECT_TRUE(from_json(to_json(req), back.back(), &json_error)) << json_error;
  EXPECT_EQ(topic_error, "");
  EXPECT_EQ(service_error, "");
  return back;
}

TEST(RequestKinds, CssCalibrationRoundTripsTheWireTheServiceAndJson) {
  const ScanRequest css = css_calibrate_request();
  const RequestOut out(css, false);
  EXPECT_DOUBLE_EQ(out.msg().target_radius, 0.0127);  // metres on the wire
  EXPECT_TRUE(out.msg().robot_pose_given);
  EXPECT_NEAR(out.msg().robot_pose.position.z, 0.61, 1e-12);
  for (const ScanRequest& back : decoded_three_ways(css, out, 3)) {
    EXPECT_EQ(back.id, "css-3");
    EXPECT_EQ(back.kind, DetectKind::kCalibrate);
    EXPECT_EQ(back.target.kind, "css");
    EXPECT_NEAR(back.target.radius_mm, 12.7, 1e-9);
    ASSERT_TRUE(back.target.T_base_joint);
    EXPECT_TRUE(back.target.T_base_joint->isApprox(*css.target.T_base_joint, 1e-9));
    EXPECT_EQ(back.target.scans, css.target.scans);
  }
  std::string topic_error, json_error;
  ScanRequest json = css;  // a request that holds a css target
  // Not given: nothing on the wire says otherwise, and JSON leaves the fields out.
  const ScanRequest stripe = calibrate_request();
  const RequestOut stripe_out(stripe, false);
  EXPECT_FALSE(stripe_out.msg().robot_pose_given);
  EXPECT_EQ(stripe_out.msg().calibration_scans._length, 0u);
  const ScanRequest stripe_back = from_msg(stripe_out.msg(), &topic_error);
  EXPECT_EQ(topic_error, "");
  EXPECT_EQ(stripe_back.target.radius_mm, 0.0);
  EXPECT_FALSE(stripe_back.target.T_base_joint);
  EXPECT_TRUE(stripe_back.target.scans.empty());
  const nlohmann::json stripe_json = to_json(stripe);
  for (const char* field : {"radius_mm", "robot_pose", "scans"}) {
    EXPECT_FALSE(stripe_json.at("target").contains(field)) << field;
  }
  // A request read into one that held a css target keeps none of it.
  ASSERT_TRUE(from_json(stripe_json, json, &json_error)) << json_error;
  EXPECT_EQ(json.target.kind, "stripe");
  EXPECT_EQ(json.target.radius_mm, 0.0);
  EXPECT_FALSE(json.target.T_base_joint);
  EXPECT_TRUE(json.target.scans.empty());
  // A malformed robot pose is named as such.
  nlohmann::json bad = to_json(css);
  bad["target"]["robot_pose"] = {1.0, 2.0, 3.0};
  EXPECT_FALSE(from_json(bad, json, &json_error));
  EXPECT_EQ(json_error, "request: target.robot_pose must be [x, y, z, roll, pitch, yaw]");
}

TEST(RequestKinds, PantiltCalibrationRoundTripsTheWireTheServiceAndJson) {
  const ScanRequest pantilt = pantilt_calibrate_request();
  const RequestOut out(pantilt, false);
  EXPECT_TRUE(out.msg().target_tilt_given);
  EXPECT_EQ(out.msg().target_tilt, 0.35);  // radians on the wire, as given
  EXPECT_NEAR(out.msg().target_pose.position.x, 0.9, 1e-12);
  for (const ScanRequest& back : decoded_three_ways(pantilt, out, 4)) {
    EXPECT_EQ(back.id, "sweep-2");
    EXPECT_EQ(back.kind, DetectKind::kCalibrate);
    EXPECT_EQ(back.target.kind, "pantilt");
    EXPECT_NEAR(back.target.edge_mm, 100.0, 1e-9);
    EXPECT_NEAR(back.target.bar_mm, 10.0, 1e-9);
    EXPECT_TRUE(back.target.T_table_target.isApprox(pantilt.target.T_table_target, 1e-9));
    ASSERT_TRUE(back.target.tilt_rad);
    EXPECT_EQ(*back.target.tilt_rad, 0.35);
    EXPECT_EQ(back.target.scans, pantilt.target.scans);
    EXPECT_FALSE(back.target.T_base_joint);
  }
  std::string topic_error, json_error;
  ScanRequest json = pantilt;  // a request that holds a tilt
  // Not given: target_tilt_given false on the wire and no tilt_rad in JSON.
  const ScanRequest stripe = calibrate_request();
  const RequestOut stripe_out(stripe, false);
  EXPECT_FALSE(stripe_out.msg().target_tilt_given);
  EXPECT_EQ(stripe_out.msg().target_tilt, 0.0);
  EXPECT_FALSE(from_msg(stripe_out.msg(), &topic_error).target.tilt_rad);
  EXPECT_EQ(topic_error, "");
  const nlohmann::json stripe_json = to_json(stripe);
  EXPECT_FALSE(stripe_json.at("target").contains("tilt_rad"));
  // A pantilt request without a tilt (whatever the head reports) stays without one.
  ScanRequest untilted = pantilt;
  untilted.target.tilt_rad.reset();
  const RequestOut untilted_out(untilted, false);
  EXPECT_FALSE(untilted_out.msg().target_tilt_given);
  EXPECT_FALSE(from_msg(untilted_out.msg(), &topic_error).target.tilt_rad);
  EXPECT_EQ(topic_error, "");
  EXPECT_FALSE(to_json(untilted).at("target").contains("tilt_rad"));
  // A request read into one that held a tilt keeps none of it.
  ASSERT_TRUE(from_json(stripe_json, json, &json_error)) << json_error;
  EXPECT_EQ(json.target.kind, "stripe");
  EXPECT_FALSE(json.target.tilt_rad);
  EXPECT_TRUE(json.target.scans.empty());
}

TEST(RequestKinds, AnOlderClientsRequestHasNoPipeAndNoSensorOverride) {
  ScanRequest req;
  req.id = "old";
  req.bore.radius_mm = 5.0;
  const RequestOut out(req, false);
  std::string error;
  ScanRequest back = from_msg(out.msg(), &error);
  EXPECT_EQ(error, "");
  EXPECT_FALSE(back.view_dir);
  EXPECT_FALSE(back.sensor_position);
  EXPECT_EQ(back.bore.outer_radius_mm, 0.0);
  EXPECT_EQ(validate_request(back, css_and_stripe()), "");
  EXPECT_EQ(back.bore.walls, "inner");
  // A JSON request with only a kind and a prior, as the HTTP/TCP interfaces take it.
  ScanRequest json;
  nlohmann::json full = to_json(ScanRequest{});
  full.merge_patch(nlohmann::json::parse(
      R"({"id": "j", "kind": "bore", "bore": {"position_mm": [0, 0, 285.8], "axis": [0, 0, 1],
          "radius_mm": 6, "outer_radius_mm": 8, "walls": "outer"}, "view_dir": [0, 0, 2]})"));
  ASSERT_TRUE(from_json(full, json, &error)) << error;
  EXPECT_EQ(validate_request(json, css_and_stripe()), "");
  EXPECT_EQ(json.bore.walls, "outer");
  EXPECT_EQ(*json.view_dir, Eigen::Vector3d::UnitZ());  // normalised
}

TEST(RequestKinds, ValidationNamesWhatIsWrong) {
  const DaemonConfig config = css_and_stripe();
  const auto reason = [&](auto change) {
    ScanRequest r = pipe_request();
    change(r);
    return validate_request(r, config);
  };
  EXPECT_EQ(reason([](ScanRequest&) {}), "");
  EXPECT_EQ(reason([](ScanRequest& r) { r.bore.walls = "middle"; }),
            "bore walls must be \"inner\", \"outer\" or \"both\"");
  EXPECT_EQ(reason([](ScanRequest& r) { r.bore.outer_radius_mm = 5.0; }),
            "bore walls \"both\" needs outer_radius larger than radius");
  EXPECT_EQ(reason([](ScanRequest& r) { r.bore.normal_keep = 1.5; }),
            "bore normal_keep must be in (0, 1] (0: all)");
  EXPECT_EQ(reason([](ScanRequest& r) { r.view_dir = Eigen::Vector3d::Zero(); }),
            "view_dir must be finite and not zero");
  ScanRequest learn;
  learn.id = "l";
  learn.kind = DetectKind::kLearn;
  learn.parts = 3;
  EXPECT_EQ(validate_request(learn, config), "parts must be 1 or 2 (0: 1)");
  learn.parts = 0;
  EXPECT_EQ(validate_request(learn, config), "");
  EXPECT_EQ(learn.model, "learnt");
  EXPECT_EQ(learn.sensor, "stripe");
  // Several sensors for a learn: known, once each, each over its configured sweep.
  const auto views = [&](std::vector<std::string> sensors, auto change) {
    ScanRequest r;
    r.id = "v";
    r.kind = DetectKind::kLearn;
    r.sensors = std::move(sensors);
    change(r);
    return validate_request(r, config);
  };
  const auto same = [](ScanRequest&) {};
  EXPECT_EQ(views({"stripe", "css"}, same), "");
  EXPECT_EQ(views({"stripe", "head"}, same), "unknown sensor \"head\" in sensors");
  EXPECT_EQ(views({"stripe", "stripe"}, same), "sensor \"stripe\" named twice in sensors");
  EXPECT_EQ(views({"stripe", "css", "stripe2", "css2", "x"}, same),
            "sensors: at most 4 scans are fused");
  EXPECT_EQ(views({"stripe", "css"}, [](ScanRequest& r) { r.sensor = "css"; }),
            "give sensor or sensors, not both");
  EXPECT_EQ(views({"stripe", "css"}, [](ScanRequest& r) { r.sweep_end = 100.0; }),
            "with sensors each scans its configured sweep: leave sweep out");
  EXPECT_EQ(views({"stripe", "css"}, [](ScanRequest& r) { r.kind = DetectKind::kBore; }),
            "sensors (several scans fused) is for learn, object and stripe calibrate requests; "
            "give one sensor");
  // An object request fuses the two cameras of one laser plane: two stripe devices, or two
  // pan_tilt devices.
  const auto object = [](ScanRequest& r) {
    r.kind = DetectKind::kObject;
    r.model = "mallet";
  };
  EXPECT_EQ(views({"stripe", "css"}, object),
            "sensors: \"css\" is a css; an object request fuses the cameras of a stripe cell or "
            "a pan-tilt head");
  DaemonConfig with_head = config;
  DeviceConfig head;
  head.name = head.kind = "pan_tilt";
  with_head.devices.push_back(head);
  ScanRequest mixed;
  mixed.id = "m";
  mixed.sensors = {"stripe", "pan_tilt"};
  object(mixed);
  EXPECT_EQ(validate_request(mixed, with_head),
            "sensors: \"pan_tilt\" is a pan_tilt, \"stripe\" a stripe; an object request fuses "
            "two cameras of one laser plane");
  EXPECT_EQ(views({"stripe", "stripe2", "css"}, object),
            "sensors: an object request fuses the two cameras of one laser plane; name two");
  ScanRequest fused;
  fused.id = "f";
  fused.kind = DetectKind::kLearn;
  fused.sensors = {"css", "stripe"};
  EXPECT_EQ(validate_request(fused, config), "");
  EXPECT_EQ(fused.sensor, "css");  // the first, with its configured sweep
  ScanRequest cal = calibrate_request();
  EXPECT_EQ(validate_request(cal, config), "");
  EXPECT_EQ(cal.sensor, "stripe");  // the stripe target's sensor
  cal = calibrate_request();
  cal.sensor = "css";
  EXPECT_EQ(validate_request(cal, config),
            "calibrate stripe needs a stripe sensor; \"css\" is a css");
  // A stripe calibration takes the cameras of its laser plane together; other targets one.
  DaemonConfig two_cameras = config;
  DeviceConfig stripe2;
  stripe2.name = "stripe2";
  stripe2.kind = "stripe";
  two_cameras.devices.push_back(stripe2);
  cal = calibrate_request();
  cal.sensors = {"stripe", "stripe2"};
  EXPECT_EQ(validate_request(cal, two_cameras), "");
  EXPECT_EQ(cal.sensor, "stripe");
  cal.sensors = {"stripe", "css"};
  EXPECT_EQ(validate_request(cal, config),
            "sensors: \"css\" is a css; a stripe calibration takes the cameras of its laser "
            "plane");
  cal = calibrate_request();
  cal.target.kind = "css";
  cal.target.radius_mm = 25.0;
  cal.sensors = {"css", "css2"};
  EXPECT_EQ(validate_request(cal, config),
            "sensors: a calibrate request takes several sensors for the stripe target only (the "
            "cameras of its laser plane, one sweep); give one sensor");
  cal = calibrate_request();
  cal.target.bar_mm = 100.0;
  EXPECT_EQ(validate_request(cal, config),
            "target size must be an edge > 0 and a bar in (0, edge / 2), mm");
  // An unknown kind on the wire is refused by name.
  ScanRequest bad = pipe_request();
  RequestOut out(bad, false);
  rangefit_msgs_msg_dds__DetectRequest_ msg = out.msg();
  msg.kind = const_cast<char*>("teach");
  std::string error;
  (void)from_msg(msg, &error);
  EXPECT_EQ(error,
            "unknown kind \"teach\" (expected \"bore\", \"object\", \"learn\" or \"calibrate\")");
}

}  // namespace request_kinds_test
}  // namespace rangefit::daemon
