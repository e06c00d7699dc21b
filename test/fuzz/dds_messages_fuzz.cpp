// DDS messages as they arrive off the wire: a serialized sample (the 4-byte encapsulation header
// and its XCDR body, either byte order) goes through Cyclone's own receive path for its type, as
// ddsi_serdata_default.c does it (the body is checked and byte-swapped by
// dds_stream_normalize_data, dropped when that fails, then read into the sample by
// dds_stream_read), and on to the project's decoding: the PointCloud2, Detection and
// DiagnosticArray that `rangefit watch` and `rangefit request` read, and the DetectRequest that
// rangefitd reads and validates against its configuration before logging or queueing it, from
// the topic or as a ROS 2 service request (rq/rangefit/detectRequest: rmw_cyclonedds's request
// header, the caller's 64-bit writer id and sequence number, then the same fields). The first
// input byte picks the message; the rest is the serialized sample. The seeds
// (corpus/dds_messages) are such samples of CloudOut, RequestOut, DetectionOut and DiagnosticsOut
// as Cyclone's dds_stream_write serializes them, in both byte orders, the PointCloud2 of
// width = height = 2^31 that once made `rangefit watch` exit, and service requests (service_*):
// topic request seeds with the 16-byte header in front (the fields keep their alignment), with
// and without an id, one without an id and with a NaN in the target pose; and a request and a
// service request whose NaN bore_major_axis (unused without bore_radius2) was accepted
// (crash-*-nan-major-axis-accepted), and the object service request with a NaN bore_half_angle
// this harness found accepted (crash-service-request-object-nan-bore-half-angle-accepted): an
// accepted request has only finite numbers on the wire.
#include <dds/dds.h>
#include <dds/ddsi/ddsi_cdrstream.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "daemon/dds/cloud_msg_guard.hpp"
#include "daemon/dds/messages.hpp"
#include "daemon/dds/service_request.hpp"
#include "daemon/service/config.hpp"
#include "daemon/service/log_escape.hpp"
#include "daemon/service/request_validation.hpp"
#include "test/fuzz/wire_sample.hpp"

namespace {

using namespace rangefit::daemon;
using rangefit::test::WireSample;

// What rangefitd runs with: a CSS (bore, angular sweep), a stripe (objects, linear sweep) and
// one object model, so a request can pass validation for every kind.
const DaemonConfig& daemon_config() {
  static const DaemonConfig config = [] {
    const ConfigResult r = parse_config(
        "[service]\nbore_sensor = \"css\"\nobject_sensor = \"stripe\"\n"
        "[[devices]]\nname = \"css\"\nkind = \"css\"\ndriver = \"replay\"\n"
        "replay_file = \"scan.ply\"\n"
        "[[devices]]\nname = \"stripe\"\nkind = \"stripe\"\ndriver = \"replay\"\n"
        "replay_file = \"scan.ply\"\n"
        "[[objects]]\nname = \"box\"\nscale_mm = [40.0, 30.0, 20.0]\nshape = [0.1, 0.1]\n",
        "dds_messages_fuzz");
    if (!r.config) std::abort();  // the harness's own configuration must be valid
    return *r.config;
  }();
  return config;
}

void cloud(std::span<const std::uint8_t> bytes) {
  const WireSample<sensor_msgs_msg_dds__PointCloud2_> msg(sensor_msgs_msg_dds__PointCloud2__desc,
                                                          bytes);
  if (msg.get() == nullptr) return;
  const rangefit::PointCloud c = cloud_from_wire(*msg.get());
  // Never more points than the message claims, and only finite ones.
  if (c.size() > std::uint64_t{msg.get()->width} * msg.get()->height) std::abort();
  for (const auto& p : c.points) {
    if (!p.allFinite()) std::abort();
  }
}

void detection(std::span<const std::uint8_t> bytes) {
  const WireSample<rangefit_msgs_msg_dds__Detection_> msg(rangefit_msgs_msg_dds__Detection__desc,
                                                          bytes);
  if (msg.get() != nullptr) (void)from_msg(*msg.get());
}

void diagnostics(std::span<const std::uint8_t> bytes) {
  const WireSample<diagnostic_msgs_msg_dds__DiagnosticArray_> msg(
      diagnostic_msgs_msg_dds__DiagnosticArray__desc, bytes);
  if (msg.get() != nullptr) (void)from_msg(*msg.get());
}

// Every number of a request on the wire (topic and service share the field names).
template <class Msg>
bool wire_numbers_finite(const Msg& m) {
  const auto point = [](const auto& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  };
  const auto& q = m.target_pose.orientation;
  return point(m.bore_position) && point(m.bore_axis) && std::isfinite(m.bore_radius) &&
         std::isfinite(m.sweep_start) && std::isfinite(m.sweep_end) &&
         std::isfinite(m.sweep_speed) && point(m.bore_plane_normal) &&
         std::isfinite(m.bore_outer_radius) && std::isfinite(m.bore_normal_keep) &&
         point(m.view_dir) && point(m.sensor_position) && std::isfinite(m.target_edge) &&
         std::isfinite(m.target_bar) && point(m.target_pose.position) && std::isfinite(q.x) &&
         std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w) &&
         std::isfinite(m.bore_half_angle) && std::isfinite(m.bore_cylinder_radius) &&
         std::isfinite(m.bore_radius2) && point(m.bore_major_axis) &&
         std::isfinite(m.target_radius) && point(m.robot_pose.position) &&
         std::isfinite(m.robot_pose.orientation.x) && std::isfinite(m.robot_pose.orientation.y) &&
         std::isfinite(m.robot_pose.orientation.z) && std::isfinite(m.robot_pose.orientation.w) &&
         std::isfinite(m.target_tilt);
}

// What rangefitd does with a decoded request (either way it came): validate it, log a rejected
// one's id escaped, queue an accepted one. Returns whether it was accepted.
bool check_request(ScanRequest req, std::string error) {
  if (error.empty()) error = validate_request(req, daemon_config());
  // A rejected request's id is logged escaped: printable ASCII only may reach the log.
  for (const char ch : log_escape(req.id)) {
    if (static_cast<unsigned char>(ch) < 0x20 || static_cast<unsigned char>(ch) >= 0x7f) {
      std::abort();
    }
  }
  if (!error.empty()) return false;
  // What validation lets through is bounded: a printable id and a sweep within one turn / 10 m.
  if (!check_name(req.id, "request_id", kMaxRequestIdLength).empty()) std::abort();
  if (!(std::abs(req.sweep_start) <= 1e4 && std::abs(req.sweep_end) <= 1e4)) std::abort();
  return true;
}

void request(std::span<const std::uint8_t> bytes) {
  const WireSample<rangefit_msgs_msg_dds__DetectRequest_> msg(
      rangefit_msgs_msg_dds__DetectRequest__desc, bytes);
  if (msg.get() == nullptr) return;
  std::string error;
  ScanRequest req = from_msg(*msg.get(), &error);
  // A non-finite number is refused, never dropped or replaced by a default and accepted.
  if (check_request(std::move(req), std::move(error)) && !wire_numbers_finite(*msg.get())) {
    std::abort();
  }
}

void service_request(std::span<const std::uint8_t> bytes) {
  const WireSample<rangefit_msgs_srv_dds__Detect_Request_> msg(
      rangefit_msgs_srv_dds__Detect_Request__desc, bytes);
  if (msg.get() == nullptr) return;
  const auto& m = *msg.get();
  std::string error;
  ScanRequest req = from_service_request(m, &error);
  // A call without an id is named after the caller, so its answer can find it.
  if ((m.request_id == nullptr || m.request_id[0] == '\0') && req.id != service_call_id(m)) {
    std::abort();
  }
  if (req.id.empty()) std::abort();
  if (check_request(std::move(req), std::move(error)) && !wire_numbers_finite(m)) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::span<const std::uint8_t> sample(data + 1, size - 1);
  switch (data[0] % 5) {
    case 0:
      cloud(sample);
      break;
    case 1:
      request(sample);
      break;
    case 2:
      detection(sample);
      break;
    case 3:
      diagnostics(sample);
      break;
    default:
      service_request(sample);
      break;
  }
  return 0;
}
