// A /rangefit/detect service request (rmw_cyclonedds framing: caller id, sequence number, then
// the DetectRequest fields) is read with every check a topic request gets, also when the caller
// left the id empty and the daemon names the request after the call.
#include "daemon/dds/service_request.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace rangefit::daemon {
namespace service_request_test {

char* text(const char* s) { return const_cast<char*>(s); }  // the wire struct only reads it

rangefit_msgs_srv_dds__Detect_Request_ bore_call(const char* id) {
  rangefit_msgs_srv_dds__Detect_Request_ m{};
  m.rmw_client_guid = 0x01c2f00dull;
  m.rmw_sequence_number = 7;
  m.request_id = text(id);
  m.kind = text("bore");
  m.model = text("");
  m.sensor = text("");
  m.bore_walls = text("");
  m.target = text("");
  m.bore_axis.z = 1.0;
  m.bore_radius = 0.005;
  m.target_pose.orientation.w = 1.0;
  m.robot_pose.orientation.w = 1.0;
  return m;
}

TEST(ServiceRequest, ACallWithoutIdIsNamedAfterTheCaller) {
  std::string error;
  const ScanRequest req = from_service_request(bore_call(""), &error);
  EXPECT_EQ(error, "");
  EXPECT_EQ(req.id, "ros-0000000001c2f00d-7");
  EXPECT_EQ(req.kind, DetectKind::kBore);
  EXPECT_DOUBLE_EQ(req.bore.radius_mm, 5.0);
}

TEST(ServiceRequest, AGivenIdIsKept) {
  std::string error;
  const ScanRequest req = from_service_request(bore_call("cell-3"), &error);
  EXPECT_EQ(error, "");
  EXPECT_EQ(req.id, "cell-3");
}

TEST(ServiceRequest, NonFiniteNumbersAreRefusedAlsoWhenTheIdIsLeftToTheCall) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const char* id : {"cell-3", ""}) {
    auto m = bore_call(id);
    m.target_pose.orientation.w = nan;  // would silently become the identity rotation
    std::string error;
    (void)from_service_request(m, &error);
    EXPECT_EQ(error, "non-finite number in request") << "id \"" << id << "\"";
    m = bore_call(id);
    m.bore_position.x = nan;
    (void)from_service_request(m, &error);
    EXPECT_EQ(error, "non-finite number in request") << "id \"" << id << "\"";
    m = bore_call(id);
    m.bore_major_axis.x = nan;  // unused without bore_radius2, still not a number to accept
    (void)from_service_request(m, &error);
    EXPECT_EQ(error, "non-finite number in request") << "id \"" << id << "\"";
    m = bore_call(id);
    m.kind = text("object");
    m.model = text("box");
    m.bore_half_angle = nan;  // a bore field in an object request: unused, still refused
    (void)from_service_request(m, &error);
    EXPECT_EQ(error, "non-finite number in request") << "id \"" << id << "\"";
    m = bore_call(id);
    m.target_radius = std::numeric_limits<double>::infinity();
    (void)from_service_request(m, &error);
    EXPECT_EQ(error, "non-finite number in request") << "id \"" << id << "\"";
    m = bore_call(id);
    m.robot_pose.position.y = nan;  // robot_pose_given false: unused, still refused
    (void)from_service_request(m, &error);
    EXPECT_EQ(error, "non-finite number in request") << "id \"" << id << "\"";
    m = bore_call(id);
    m.robot_pose_given = true;
    m.robot_pose.orientation.w = nan;  // would silently become the identity rotation
    (void)from_service_request(m, &error);
    EXPECT_EQ(error, "non-finite number in request") << "id \"" << id << "\"";
    m = bore_call(id);
    m.target_tilt = nan;  // target_tilt_given false: unused, still refused
    (void)from_service_request(m, &error);
    EXPECT_EQ(error, "non-finite number in request") << "id \"" << id << "\"";
    m = bore_call(id);
    m.target_tilt_given = true;
    m.target_tilt = nan;
    (void)from_service_request(m, &error);
    EXPECT_EQ(error, "non-finite number in request") << "id \"" << id << "\"";
  }
}

TEST(ServiceRequest, AnUnknownKindIsNamedBeforeTheMissingId) {
  auto m = bore_call("");
  m.kind = text("teleport");
  std::string error;
  (void)from_service_request(m, &error);
  EXPECT_NE(error.find("unknown kind \"teleport\""), std::string::npos) << error;
}

}  // namespace service_request_test
}  // namespace rangefit::daemon
