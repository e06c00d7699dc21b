#include "daemon/dds/messages.hpp"
#include "daemon/dds/dds_chars.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>

namespace rangefit::daemon {
namespace {

std::string str(const char* s) { return s == nullptr ? std::string() : std::string(s); }

std_msgs_msg_dds__Header_ header(const std::string& frame) {
  return {wall_time_now(), dds_chars(frame)};
}

constexpr std::uint8_t kFloat32 = 7, kFloat64 = 8;  // sensor_msgs/PointField datatypes

// A pose in mm as geometry_msgs/Pose: metres and a quaternion.
geometry_msgs_msg_dds__Pose_ pose_msg(const Eigen::Isometry3d& T) {
  const Eigen::Vector3d t = T.translation() * kMetresPerMm;
  const Eigen::Quaterniond q(T.rotation());
  return {{t.x(), t.y(), t.z()}, {q.x(), q.y(), q.z(), q.w()}};
}

// A geometry_msgs/Pose back in mm. A zero or non-finite quaternion leaves the rotation the
// identity; a request refuses the non-finite one (finite_quaternion).
Eigen::Isometry3d pose_mm(const geometry_msgs_msg_dds__Pose_& p) {
  const Eigen::Quaterniond q(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  if (q.coeffs().allFinite() && q.norm() > 0) T.linear() = q.normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z) / kMetresPerMm;
  return T;
}

bool finite_quaternion(const geometry_msgs_msg_dds__Pose_& p) {
  return std::isfinite(p.orientation.x) && std::isfinite(p.orientation.y) &&
         std::isfinite(p.orientation.z) && std::isfinite(p.orientation.w);
}

// A string sequence of the wire, at most max of its strings (a null buffer reads as empty ones).
std::vector<std::string> strings(const dds_sequence_string& seq, std::uint32_t max) {
  std::vector<std::string> out;
  for (std::uint32_t k = 0; k < std::min(seq._length, max); ++k) {
    out.push_back(seq._buffer != nullptr ? str(seq._buffer[k]) : "");
  }
  return out;
}

}  // namespace

builtin_interfaces_msg_dds__Time_ wall_time(std::int64_t ns) {
  return {static_cast<std::int32_t>(ns / 1'000'000'000),
          static_cast<std::uint32_t>(ns % 1'000'000'000)};
}

builtin_interfaces_msg_dds__Time_ wall_time_now() {
  return wall_time(std::chrono::duration_cast<std::chrono::nanoseconds>(
                       std::chrono::system_clock::now().time_since_epoch())
                       .count());
}

CloudOut::CloudOut(const PointCloud& cloud, const std::string& frame)
    : frame_(frame.empty() ? cloud.frame_id : frame) {
  names_ = {"x", "y", "z"};
  if (cloud.has_normals()) names_.insert(names_.end(), {"normal_x", "normal_y", "normal_z"});
  for (std::size_t i = 0; i < names_.size(); ++i) {
    fields_.push_back({dds_chars(names_[i]), static_cast<std::uint32_t>(4 * i), kFloat32, 1});
  }
  const std::uint32_t step = static_cast<std::uint32_t>(4 * names_.size());
  data_.resize(cloud.size() * step);
  std::uint8_t* out = data_.data();
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    float v[6];
    for (int k = 0; k < 3; ++k) v[k] = static_cast<float>(cloud.points[i][k] * kMetresPerMm);
    if (cloud.has_normals()) {
      for (int k = 0; k < 3; ++k) v[3 + k] = static_cast<float>(cloud.normals[i][k]);
    }
    std::memcpy(out, v, step);
    out += step;
  }
  msg_.header = header(frame_);
  msg_.height = 1;
  msg_.width = static_cast<std::uint32_t>(cloud.size());
  msg_.fields = {static_cast<std::uint32_t>(fields_.size()),
                 static_cast<std::uint32_t>(fields_.size()), fields_.data(), false};
  msg_.is_bigendian = std::endian::native == std::endian::big;
  msg_.point_step = step;
  msg_.row_step = step * msg_.width;
  msg_.data = {static_cast<std::uint32_t>(data_.size()), static_cast<std::uint32_t>(data_.size()),
               data_.data(), false};
  msg_.is_dense = true;
}

PointCloud from_msg(const sensor_msgs_msg_dds__PointCloud2_& msg) {
  PointCloud cloud;
  cloud.frame_id = str(msg.header.frame_id);
  int offset[3] = {-1, -1, -1};
  std::uint8_t type[3] = {};
  for (std::uint32_t i = 0; i < msg.fields._length; ++i) {
    const auto& f = msg.fields._buffer[i];
    const std::string name = str(f.name);
    const int axis = name == "x" ? 0 : name == "y" ? 1 : name == "z" ? 2 : -1;
    if (axis >= 0 && (f.datatype == kFloat32 || f.datatype == kFloat64)) {
      offset[axis] = static_cast<int>(f.offset);
      type[axis] = f.datatype;
    }
  }
  const std::uint64_t n = std::uint64_t{msg.width} * msg.height;
  // n * point_step can wrap around 2^64 (width = height = 2^31, point_step 16 gives 0), so the
  // check divides instead of multiplying; a buffer too short for n points is no cloud.
  if (offset[0] < 0 || offset[1] < 0 || offset[2] < 0 || msg.point_step == 0 ||
      n > std::uint64_t{msg.data._length} / msg.point_step) {
    return cloud;
  }
  for (int k = 0; k < 3; ++k) {
    if (static_cast<std::uint32_t>(offset[k]) + (type[k] == kFloat32 ? 4u : 8u) > msg.point_step) {
      return cloud;
    }
  }
  const bool swap = msg.is_bigendian != (std::endian::native == std::endian::big);
  cloud.points.reserve(n);
  for (std::uint64_t i = 0; i < n; ++i) {
    const std::uint8_t* p = msg.data._buffer + i * msg.point_step;
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) {
      std::uint8_t bytes[8];
      const std::size_t size = type[k] == kFloat32 ? 4 : 8;
      std::memcpy(bytes, p + offset[k], size);
      if (swap) std::reverse(bytes, bytes + size);
      if (size == 4) {
        float f;
        std::memcpy(&f, bytes, 4);
        v[k] = f;
      } else {
        std::memcpy(&v[k], bytes, 8);
      }
    }
    // Checked in mm: FLOAT64 metres near the double's limit are finite, x 1000 they are not.
    const Eigen::Vector3d mm = v / kMetresPerMm;
    if (mm.allFinite()) cloud.points.push_back(mm);
  }
  return cloud;
}

DetectionOut::DetectionOut(const DetectionResult& r, std::string frame)
    : r_(r), frame_(std::move(frame)), kind_(to_string(r.kind)) {
  for (const auto& part : r_.parts) {
    names_.push_back(dds_chars(part.name));
    const Eigen::Vector3d t = part.T_world_part.translation() * kMetresPerMm;
    const Eigen::Quaterniond q(part.T_world_part.rotation());
    poses_.push_back({{t.x(), t.y(), t.z()}, {q.x(), q.y(), q.z(), q.w()}});
    scores_.push_back(part.score);
  }
  const auto n = static_cast<std::uint32_t>(r_.parts.size());
  for (const auto& part : r_.parts) instances_.push_back(part.instance);
  msg_.header = header(frame_);
  if (r_.acquired_wall_ns > 0) msg_.header.stamp = wall_time(r_.acquired_wall_ns);
  msg_.request_id = dds_chars(r_.request_id);
  msg_.kind = dds_chars(kind_);
  msg_.found = r_.found;
  msg_.reason = dds_chars(r_.reason);
  msg_.model = dds_chars(r_.model);
  msg_.part_names = {n, n, names_.data(), false};
  msg_.poses = {n, n, poses_.data(), false};
  msg_.bore_radius = r_.bore_radius_mm * kMetresPerMm;
  msg_.scores = {n, n, scores_.data(), false};
  msg_.num_points = static_cast<std::uint32_t>(r_.num_points);
  msg_.scan_seconds = r_.scan_seconds;
  msg_.detect_seconds = r_.detect_seconds;
  msg_.spool_entry = dds_chars(r_.spool_entry);
  msg_.part_instances = {n, n, instances_.data(), false};
  details_ = r_.details.is_null() ? std::string() : r_.details.dump();
  msg_.details = dds_chars(details_);
}

geometry_msgs_msg_dds__PoseStamped_ DetectionOut::first_pose() const {
  geometry_msgs_msg_dds__PoseStamped_ p{};
  p.header = msg_.header;
  p.pose = poses_.empty() ? geometry_msgs_msg_dds__Pose_{{0, 0, 0}, {0, 0, 0, 1}} : poses_.front();
  return p;
}

DetectionResult from_msg(const rangefit_msgs_msg_dds__Detection_& msg) {
  DetectionResult r;
  r.request_id = str(msg.request_id);
  if (!kind_from_string(str(msg.kind), &r.kind)) r.kind = DetectKind::kBore;
  r.found = msg.found;
  r.reason = str(msg.reason);
  r.model = str(msg.model);
  for (std::uint32_t i = 0; i < msg.poses._length; ++i) {
    PartPose part;
    if (i < msg.part_names._length) part.name = str(msg.part_names._buffer[i]);
    if (i < msg.scores._length) part.score = msg.scores._buffer[i];
    if (i < msg.part_instances._length) part.instance = msg.part_instances._buffer[i];
    const auto& p = msg.poses._buffer[i];
    const Eigen::Quaterniond q(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z);
    part.T_world_part = Eigen::Isometry3d::Identity();
    if (q.norm() > 0) part.T_world_part.linear() = q.normalized().toRotationMatrix();
    part.T_world_part.translation() =
        Eigen::Vector3d(p.position.x, p.position.y, p.position.z) / kMetresPerMm;
    r.parts.push_back(std::move(part));
  }
  r.bore_radius_mm = msg.bore_radius / kMetresPerMm;
  r.num_points = msg.num_points;
  r.scan_seconds = msg.scan_seconds;
  r.detect_seconds = msg.detect_seconds;
  r.spool_entry = str(msg.spool_entry);
  // details is JSON the service wrote; what does not parse is dropped, never thrown.
  r.details = nlohmann::json::parse(str(msg.details), nullptr, false);
  if (r.details.is_discarded()) r.details = nullptr;
  r.acquired_wall_ns =
      std::int64_t{msg.header.stamp.sec} * 1'000'000'000 + msg.header.stamp.nanosec;
  return r;
}

RequestOut::RequestOut(const ScanRequest& req, bool linear_sweep)
    : req_(req), kind_(to_string(req.kind)), walls_(req.bore.walls), target_(req.target.kind) {
  convert_sweep_units(req_, linear_sweep, true);
  msg_.request_id = dds_chars(req_.id);
  msg_.kind = dds_chars(kind_);
  msg_.model = dds_chars(req_.model);
  const Eigen::Vector3d p = req_.bore.position_mm * kMetresPerMm;
  msg_.bore_position = {p.x(), p.y(), p.z()};
  msg_.bore_axis = {req_.bore.axis.x(), req_.bore.axis.y(), req_.bore.axis.z()};
  msg_.bore_radius = req_.bore.radius_mm * kMetresPerMm;
  msg_.sensor = dds_chars(req_.sensor);
  msg_.sweep_start = req_.sweep_start;
  msg_.sweep_end = req_.sweep_end;
  msg_.sweep_speed = req_.sweep_speed;
  const Eigen::Vector3d n = req_.bore.plane_normal.value_or(Eigen::Vector3d::Zero());
  msg_.bore_plane_normal = {n.x(), n.y(), n.z()};
  msg_.instances = static_cast<std::uint32_t>(std::max(req_.instances, 0));
  msg_.hypotheses = static_cast<std::uint32_t>(std::max(req_.hypotheses, 0));
  msg_.trials = static_cast<std::uint32_t>(std::max(req_.trials, 0));
  msg_.seed = req_.seed;
  msg_.bore_outer_radius = req_.bore.outer_radius_mm * kMetresPerMm;
  msg_.bore_walls = dds_chars(walls_);
  msg_.bore_normal_keep = req_.bore.normal_keep;
  const Eigen::Vector3d v = req_.view_dir.value_or(Eigen::Vector3d::Zero());
  msg_.view_dir = {v.x(), v.y(), v.z()};
  msg_.sensor_position_given = req_.sensor_position.has_value();
  const Eigen::Vector3d sp = req_.sensor_position.value_or(Eigen::Vector3d::Zero()) * kMetresPerMm;
  msg_.sensor_position = {sp.x(), sp.y(), sp.z()};
  msg_.parts = static_cast<std::uint32_t>(std::max(req_.parts, 0));
  msg_.target = dds_chars(target_);
  msg_.target_edge = req_.target.edge_mm * kMetresPerMm;
  msg_.target_bar = req_.target.bar_mm * kMetresPerMm;
  msg_.target_pose = pose_msg(req_.target.T_table_target);
  msg_.bore_half_angle = req_.bore.half_angle_rad;
  msg_.bore_cylinder_radius = req_.bore.cylinder_radius_mm * kMetresPerMm;
  msg_.bore_radius2 = req_.bore.radius2_mm * kMetresPerMm;
  const Eigen::Vector3d ma = req_.bore.major_axis.value_or(Eigen::Vector3d::Zero());
  msg_.bore_major_axis = {ma.x(), ma.y(), ma.z()};
  for (std::string& name : req_.sensors) sensors_.push_back(dds_chars(name));
  const auto ns = static_cast<std::uint32_t>(sensors_.size());
  msg_.sensors = {ns, ns, sensors_.data(), false};
  msg_.target_radius = req_.target.radius_mm * kMetresPerMm;
  // Not given: robot_pose_given false and the identity pose, which the reader ignores.
  msg_.robot_pose_given = req_.target.T_base_joint.has_value();
  msg_.robot_pose = pose_msg(req_.target.T_base_joint.value_or(Eigen::Isometry3d::Identity()));
  for (std::string& id : req_.target.scans) scans_.push_back(dds_chars(id));
  const auto nc = static_cast<std::uint32_t>(scans_.size());
  msg_.calibration_scans = {nc, nc, scans_.data(), false};
  // Not given: target_tilt_given false and a zero tilt, which the reader ignores.
  msg_.target_tilt_given = req_.target.tilt_rad.has_value();
  msg_.target_tilt = req_.target.tilt_rad.value_or(0.0);
}

ScanRequest from_msg(const rangefit_msgs_msg_dds__DetectRequest_& msg, std::string* error) {
  ScanRequest req;
  req.id = str(msg.request_id);
  const std::string kind = str(msg.kind);
  req.model = str(msg.model);
  req.sensor = str(msg.sensor);
  req.bore.position_mm =
      Eigen::Vector3d(msg.bore_position.x, msg.bore_position.y, msg.bore_position.z) / kMetresPerMm;
  req.bore.axis = Eigen::Vector3d(msg.bore_axis.x, msg.bore_axis.y, msg.bore_axis.z);
  req.bore.radius_mm = msg.bore_radius / kMetresPerMm;
  req.sweep_start = msg.sweep_start;
  req.sweep_end = msg.sweep_end;
  req.sweep_speed = msg.sweep_speed;
  const Eigen::Vector3d n(msg.bore_plane_normal.x, msg.bore_plane_normal.y,
                          msg.bore_plane_normal.z);
  if (n != Eigen::Vector3d::Zero()) req.bore.plane_normal = n;  // zero: not given
  // Counts beyond int are clamped; request validation names the field that is out of range.
  constexpr std::uint32_t kMaxCount = 1u << 30;
  req.instances = static_cast<int>(std::min(msg.instances, kMaxCount));
  req.hypotheses = static_cast<int>(std::min(msg.hypotheses, kMaxCount));
  req.trials = static_cast<int>(std::min(msg.trials, kMaxCount));
  req.seed = msg.seed;
  req.bore.outer_radius_mm = msg.bore_outer_radius / kMetresPerMm;
  req.bore.walls = str(msg.bore_walls);
  req.bore.normal_keep = msg.bore_normal_keep;
  req.bore.half_angle_rad = msg.bore_half_angle;
  req.bore.cylinder_radius_mm = msg.bore_cylinder_radius / kMetresPerMm;
  req.bore.radius2_mm = msg.bore_radius2 / kMetresPerMm;
  const Eigen::Vector3d ma(msg.bore_major_axis.x, msg.bore_major_axis.y, msg.bore_major_axis.z);
  if (ma != Eigen::Vector3d::Zero()) req.bore.major_axis = ma;  // zero: not given
  const Eigen::Vector3d v(msg.view_dir.x, msg.view_dir.y, msg.view_dir.z);
  if (v != Eigen::Vector3d::Zero()) req.view_dir = v;
  const Eigen::Vector3d sp =
      Eigen::Vector3d(msg.sensor_position.x, msg.sensor_position.y, msg.sensor_position.z) /
      kMetresPerMm;
  if (msg.sensor_position_given) req.sensor_position = sp;
  req.parts = static_cast<int>(std::min(msg.parts, kMaxCount));
  // A few more than a request may fuse, so validation names the limit; the rest is dropped.
  constexpr std::uint32_t kMaxSensors = 16;
  req.sensors = strings(msg.sensors, kMaxSensors);
  req.target.kind = str(msg.target);
  if (msg.target_edge != 0.0) req.target.edge_mm = msg.target_edge / kMetresPerMm;
  if (msg.target_bar != 0.0) req.target.bar_mm = msg.target_bar / kMetresPerMm;
  req.target.T_table_target = pose_mm(msg.target_pose);
  req.target.radius_mm = msg.target_radius / kMetresPerMm;
  // Checked below whether given or not, as sensor_position: no non-finite number is accepted.
  const Eigen::Isometry3d robot = pose_mm(msg.robot_pose);
  if (msg.robot_pose_given) req.target.T_base_joint = robot;
  // A few more than a calibration may join, so validation names the limit; the rest is dropped.
  constexpr std::uint32_t kMaxScans = 64;
  req.target.scans = strings(msg.calibration_scans, kMaxScans);
  // Checked below whether given or not, as robot_pose.
  if (msg.target_tilt_given) req.target.tilt_rad = msg.target_tilt;
  error->clear();
  if (!kind_from_string(kind, &req.kind)) {
    *error = "unknown kind \"" + kind + "\" (expected " + kKindNames + ")";
  }
  if (error->empty() && req.id.empty()) *error = "request_id is empty";
  const bool finite = req.bore.position_mm.allFinite() && req.bore.axis.allFinite() &&
                      std::isfinite(req.bore.radius_mm) && std::isfinite(req.sweep_start) &&
                      std::isfinite(req.sweep_end) && std::isfinite(req.sweep_speed) &&
                      n.allFinite() && std::isfinite(req.bore.outer_radius_mm) &&
                      std::isfinite(req.bore.normal_keep) && v.allFinite() && sp.allFinite() &&
                      std::isfinite(req.target.edge_mm) && std::isfinite(req.target.bar_mm) &&
                      req.target.T_table_target.matrix().allFinite() &&
                      finite_quaternion(msg.target_pose) && std::isfinite(req.target.radius_mm) &&
                      robot.matrix().allFinite() && finite_quaternion(msg.robot_pose) &&
                      std::isfinite(msg.target_tilt) && std::isfinite(req.bore.half_angle_rad) &&
                      std::isfinite(req.bore.cylinder_radius_mm) &&
                      std::isfinite(req.bore.radius2_mm) && ma.allFinite();
  if (error->empty() && !finite) *error = "non-finite number in request";
  return req;
}

StateOut::StateOut(LifecycleState s, std::string detail, std::string active_id, std::uint32_t depth,
                   std::string frame)
    : frame_(std::move(frame)), detail_(std::move(detail)), active_(std::move(active_id)) {
  msg_.header = header(frame_);
  msg_.state = static_cast<std::uint8_t>(s);
  msg_.detail = dds_chars(detail_);
  msg_.active_request_id = dds_chars(active_);
  msg_.queue_depth = depth;
}

DiagnosticsOut::DiagnosticsOut(std::vector<DiagStatus> statuses)
    : frame_(""), statuses_(std::move(statuses)) {
  values_.resize(statuses_.size());
  for (std::size_t i = 0; i < statuses_.size(); ++i) {
    auto& s = statuses_[i];
    for (auto& [k, v] : s.values) values_[i].push_back({dds_chars(k), dds_chars(v)});
    const auto n = static_cast<std::uint32_t>(values_[i].size());
    c_statuses_.push_back({s.level,
                           dds_chars(s.name),
                           dds_chars(s.message),
                           dds_chars(s.hardware_id),
                           {n, n, values_[i].data(), false}});
  }
  const auto n = static_cast<std::uint32_t>(c_statuses_.size());
  msg_.header = header(frame_);
  msg_.status = {n, n, c_statuses_.data(), false};
}

std::vector<DiagStatus> from_msg(const diagnostic_msgs_msg_dds__DiagnosticArray_& msg) {
  std::vector<DiagStatus> out;
  for (std::uint32_t i = 0; i < msg.status._length; ++i) {
    const auto& s = msg.status._buffer[i];
    DiagStatus d{s.level, str(s.name), str(s.message), str(s.hardware_id), {}};
    for (std::uint32_t k = 0; k < s.values._length; ++k) {
      d.values.emplace_back(str(s.values._buffer[k].key), str(s.values._buffer[k].value));
    }
    out.push_back(std::move(d));
  }
  return out;
}

}  // namespace rangefit::daemon
