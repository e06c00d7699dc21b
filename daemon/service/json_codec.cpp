#include "daemon/service/json_codec.hpp"
#include "hal/rpy.hpp"

namespace rangefit::daemon {
namespace {

Eigen::Vector3d vec_of(const nlohmann::json& j) {
  return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()};
}
DetectKind kind(const std::string& s) {
  DetectKind k = DetectKind::kBore;
  if (!kind_from_string(s, &k))
    throw std::invalid_argument(std::string("kind must be ") + kKindNames);
  return k;
}

// A pose as `rangefit calibrate --cube-pose` takes it: X, Y, Z (mm), ROLL, PITCH, YAW (rad) of
// R = Rz(yaw) Ry(pitch) Rx(roll).
nlohmann::json pose_array(const Eigen::Isometry3d& T) {
  const Eigen::Vector3d ypr = T.linear().eulerAngles(2, 1, 0);
  const Eigen::Vector3d t = T.translation();
  return {t.x(), t.y(), t.z(), ypr[2], ypr[1], ypr[0]};
}
// field: the pose's name in the request, for the error message.
Eigen::Isometry3d pose_of(const nlohmann::json& j, const std::string& field) {
  if (j.size() != 6) throw std::invalid_argument(field + " must be [x, y, z, roll, pitch, yaw]");
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = hal::rpy_matrix(j.at(3).get<double>(), j.at(4).get<double>(), j.at(5).get<double>());
  T.translation() = vec_of(j);
  return T;
}

}  // namespace

nlohmann::json to_json(const ScanRequest& r) {
  nlohmann::json j = {{"id", r.id},
                      {"kind", to_string(r.kind)},
                      {"model", r.model},
                      {"bore",
                       {{"position_mm", json_vec(r.bore.position_mm)},
                        {"axis", json_vec(r.bore.axis)},
                        {"radius_mm", r.bore.radius_mm}}},
                      {"sensor", r.sensor},
                      {"sweep", {r.sweep_start, r.sweep_end, r.sweep_speed}},
                      {"instances", r.instances},
                      {"hypotheses", r.hypotheses},
                      {"trials", r.trials},
                      {"seed", r.seed}};
  if (r.bore.plane_normal) j["bore"]["plane_normal"] = json_vec(*r.bore.plane_normal);
  if (r.bore.outer_radius_mm > 0.0) j["bore"]["outer_radius_mm"] = r.bore.outer_radius_mm;
  if (!r.bore.walls.empty()) j["bore"]["walls"] = r.bore.walls;
  if (r.bore.normal_keep > 0.0) j["bore"]["normal_keep"] = r.bore.normal_keep;
  if (r.bore.half_angle_rad != 0.0) j["bore"]["half_angle_rad"] = r.bore.half_angle_rad;
  if (r.bore.cylinder_radius_mm != 0.0) j["bore"]["cylinder_radius_mm"] = r.bore.cylinder_radius_mm;
  if (r.bore.radius2_mm != 0.0) j["bore"]["radius2_mm"] = r.bore.radius2_mm;
  if (r.bore.major_axis) j["bore"]["major_axis"] = json_vec(*r.bore.major_axis);
  if (r.view_dir) j["view_dir"] = json_vec(*r.view_dir);
  if (r.sensor_position) j["sensor_position_mm"] = json_vec(*r.sensor_position);
  if (r.parts != 0) j["parts"] = r.parts;
  if (!r.sensors.empty()) j["sensors"] = r.sensors;
  if (!r.target.kind.empty()) {
    j["target"] = {{"kind", r.target.kind},
                   {"size_mm", {r.target.edge_mm, r.target.bar_mm}},
                   {"pose", pose_array(r.target.T_table_target)}};
    if (r.target.radius_mm > 0.0) j["target"]["radius_mm"] = r.target.radius_mm;
    if (r.target.T_base_joint) j["target"]["robot_pose"] = pose_array(*r.target.T_base_joint);
    if (!r.target.scans.empty()) j["target"]["scans"] = r.target.scans;
    if (r.target.tilt_rad) j["target"]["tilt_rad"] = *r.target.tilt_rad;
  }
  return j;
}

nlohmann::json to_json(const DetectionResult& r) {
  nlohmann::json parts = nlohmann::json::array();
  for (const auto& p : r.parts) {
    const Eigen::Quaterniond q(p.T_world_part.rotation());
    parts.push_back({{"name", p.name},
                     {"translation_mm", json_vec(p.T_world_part.translation())},
                     {"quaternion_wxyz", {q.w(), q.x(), q.y(), q.z()}},
                     {"score", p.score},
                     {"instance", p.instance}});
  }
  nlohmann::json j = {{"request_id", r.request_id},
                      {"kind", to_string(r.kind)},
                      {"model", r.model},
                      {"found", r.found},
                      {"reason", r.reason},
                      {"parts", parts},
                      {"bore_radius_mm", r.bore_radius_mm},
                      {"num_points", r.num_points},
                      {"scan_seconds", r.scan_seconds},
                      {"detect_seconds", r.detect_seconds},
                      {"spool_entry", r.spool_entry},
                      {"acquired_wall_ns", r.acquired_wall_ns}};
  if (!r.details.is_null()) j["details"] = r.details;
  return j;
}

bool from_json(const nlohmann::json& j, ScanRequest& out, std::string* error) {
  try {
    out.id = j.at("id").get<std::string>();
    out.kind = kind(j.at("kind").get<std::string>());
    out.model = j.at("model").get<std::string>();
    out.bore.position_mm = vec_of(j.at("bore").at("position_mm"));
    out.bore.axis = vec_of(j.at("bore").at("axis"));
    out.bore.radius_mm = j.at("bore").at("radius_mm").get<double>();
    out.sensor = j.at("sensor").get<std::string>();
    out.sweep_start = j.at("sweep").at(0).get<double>();
    out.sweep_end = j.at("sweep").at(1).get<double>();
    out.sweep_speed = j.at("sweep").at(2).get<double>();
    // Absent in entries spooled before these fields existed.
    if (j.at("bore").contains("plane_normal")) {
      out.bore.plane_normal = vec_of(j.at("bore").at("plane_normal"));
    }
    out.instances = j.value("instances", 1);
    out.hypotheses = j.value("hypotheses", 0);
    out.trials = j.value("trials", 0);
    out.seed = j.value("seed", std::uint64_t{0});
    const auto& bore = j.at("bore");
    out.bore.outer_radius_mm = bore.value("outer_radius_mm", 0.0);
    out.bore.walls = bore.value("walls", std::string());
    out.bore.normal_keep = bore.value("normal_keep", 0.0);
    out.bore.half_angle_rad = bore.value("half_angle_rad", 0.0);
    out.bore.cylinder_radius_mm = bore.value("cylinder_radius_mm", 0.0);
    out.bore.radius2_mm = bore.value("radius2_mm", 0.0);
    out.bore.major_axis.reset();
    if (bore.contains("major_axis")) out.bore.major_axis = vec_of(bore.at("major_axis"));
    out.view_dir.reset();
    out.sensor_position.reset();
    if (j.contains("view_dir")) out.view_dir = vec_of(j.at("view_dir"));
    if (j.contains("sensor_position_mm")) out.sensor_position = vec_of(j.at("sensor_position_mm"));
    out.parts = j.value("parts", 0);
    out.sensors.clear();
    if (j.contains("sensors")) out.sensors = j.at("sensors").get<std::vector<std::string>>();
    out.target = {};
    if (j.contains("target")) {
      const auto& t = j.at("target");
      out.target.kind = t.at("kind").get<std::string>();
      if (t.contains("size_mm")) {
        out.target.edge_mm = t.at("size_mm").at(0).get<double>();
        out.target.bar_mm = t.at("size_mm").at(1).get<double>();
      }
      if (t.contains("pose")) out.target.T_table_target = pose_of(t.at("pose"), "target.pose");
      out.target.radius_mm = t.value("radius_mm", 0.0);
      if (t.contains("robot_pose")) {
        out.target.T_base_joint = pose_of(t.at("robot_pose"), "target.robot_pose");
      }
      if (t.contains("scans")) out.target.scans = t.at("scans").get<std::vector<std::string>>();
      if (t.contains("tilt_rad")) out.target.tilt_rad = t.at("tilt_rad").get<double>();
    }
    return true;
  } catch (const std::exception& e) {
    *error = std::string("request: ") + e.what();
    return false;
  }
}

bool from_json(const nlohmann::json& j, DetectionResult& out, std::string* error) {
  try {
    out.request_id = j.at("request_id").get<std::string>();
    out.kind = kind(j.at("kind").get<std::string>());
    out.model = j.at("model").get<std::string>();
    out.found = j.at("found").get<bool>();
    out.reason = j.at("reason").get<std::string>();
    out.parts.clear();
    for (const auto& p : j.at("parts")) {
      PartPose part;
      part.name = p.at("name").get<std::string>();
      const auto& q = p.at("quaternion_wxyz");
      part.T_world_part.linear() = Eigen::Quaterniond(q.at(0).get<double>(), q.at(1).get<double>(),
                                                      q.at(2).get<double>(), q.at(3).get<double>())
                                       .normalized()
                                       .toRotationMatrix();
      part.T_world_part.translation() = vec_of(p.at("translation_mm"));
      part.score = p.at("score").get<double>();
      part.instance = p.value("instance", std::uint32_t{0});
      out.parts.push_back(std::move(part));
    }
    out.bore_radius_mm = j.at("bore_radius_mm").get<double>();
    out.num_points = j.at("num_points").get<std::size_t>();
    out.scan_seconds = j.at("scan_seconds").get<double>();
    out.detect_seconds = j.at("detect_seconds").get<double>();
    out.spool_entry = j.at("spool_entry").get<std::string>();
    out.acquired_wall_ns = j.value("acquired_wall_ns", std::int64_t{0});
    out.details = j.value("details", nlohmann::json());
    return true;
  } catch (const std::exception& e) {
    *error = std::string("result: ") + e.what();
    return false;
  }
}

}  // namespace rangefit::daemon
