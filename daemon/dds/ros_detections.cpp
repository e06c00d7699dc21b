#include "daemon/dds/ros_detections.hpp"

#include "daemon/dds/dds_chars.hpp"
#include "daemon/dds/ros_frames.hpp"

namespace rangefit::daemon {
namespace {

char* empty() { return const_cast<char*>(""); }

constexpr std::int32_t kTriangleList = visualization_msgs_msg_Marker_Constants_TRIANGLE_LIST;
constexpr std::int32_t kAdd = visualization_msgs_msg_Marker_Constants_ADD;
constexpr std::int32_t kDeleteAll = visualization_msgs_msg_Marker_Constants_DELETEALL;

// Bores yellow, as the renderer draws their axis; object parts a light blue. Half transparent,
// so the scan shows through.
std_msgs_msg_dds__ColorRGBA_ colour(DetectKind kind) {
  return kind == DetectKind::kBore ? std_msgs_msg_dds__ColorRGBA_{1.0f, 0.85f, 0.1f, 0.6f}
                                   : std_msgs_msg_dds__ColorRGBA_{0.3f, 0.7f, 1.0f, 0.6f};
}

visualization_msgs_msg_dds__Marker_ blank_marker(const std_msgs_msg_dds__Header_& header) {
  visualization_msgs_msg_dds__Marker_ m{};
  m.header = header;
  m.ns = const_cast<char*>(kMarkerNamespace);
  m.pose.orientation.w = 1.0;
  m.scale = {1.0, 1.0, 1.0};  // TRIANGLE_LIST points are scaled by it
  m.texture_resource = empty();
  m.texture.header.frame_id = empty();
  m.texture.format = empty();
  m.text = empty();
  m.mesh_resource = empty();
  m.mesh_file.filename = empty();
  return m;
}

}  // namespace

Detection3DArrayOut::Detection3DArrayOut(const DetectionResult& result, std::string frame,
                                         const std::map<std::string, ObjectModel>& models,
                                         const std::string& part_frame_prefix)
    : frame_(std::move(frame)),
      class_id_(result.kind == DetectKind::kBore ? "bore" : result.model) {
  const std_msgs_msg_dds__Header_ header{result_stamp(result), dds_chars(frame_)};
  const auto& parts = result.found ? result.parts : std::vector<PartPose>{};
  ids_.reserve(parts.size());
  hypotheses_.reserve(parts.size());
  for (const PartPose& part : parts) {
    ids_.push_back(part_frame_prefix + part_frame(result, part));
    vision_msgs_msg_dds__ObjectHypothesisWithPose_ h{};
    h.hypothesis.class_id = dds_chars(class_id_);
    h.hypothesis.score = part.score;
    h.pose.pose = pose_in_metres(part.T_world_part);  // covariance unknown: zeros
    hypotheses_.push_back(h);

    vision_msgs_msg_dds__Detection3D_ d{};
    d.header = header;
    d.results = {1, 1, &hypotheses_.back(), false};
    d.id = dds_chars(ids_.back());
    // The box is aligned with the part frame, centred on the extent's centre (a bore's lies
    // below its entrance); a part of unknown shape gets a box of size zero at its pose.
    Eigen::Isometry3d T_world_box = part.T_world_part;
    if (const auto surface = part_surface(result, part, models); surface) {
      T_world_box.translation() = part.T_world_part * surface->extent.center();
      const Eigen::Vector3d size = surface->extent.sizes() * kMetresPerMm;
      d.bbox.size = {size.x(), size.y(), size.z()};
    }
    d.bbox.center = pose_in_metres(T_world_box);
    detections_.push_back(d);
  }
  const auto n = static_cast<std::uint32_t>(detections_.size());
  msg_.header = header;
  msg_.detections = {n, n, detections_.data(), false};
}

MarkerArrayOut::MarkerArrayOut(const DetectionResult& result, std::string frame,
                               const std::map<std::string, ObjectModel>& models)
    : frame_(std::move(frame)) {
  const std_msgs_msg_dds__Header_ header{result_stamp(result), dds_chars(frame_)};
  // First clear what an earlier result drew, so a part not found again disappears.
  auto clear = blank_marker(header);
  clear.action = kDeleteAll;
  markers_.push_back(clear);
  if (result.found) {
    points_.reserve(result.parts.size());
    for (const PartPose& part : result.parts) {
      const auto surface = part_surface(result, part, models);
      if (!surface) continue;
      auto& points = points_.emplace_back();
      for (const auto& t : surface->mesh.triangles) {
        for (const std::uint32_t i : t) {
          const Eigen::Vector3d p = surface->mesh.vertices[i] * kMetresPerMm;
          points.push_back({p.x(), p.y(), p.z()});
        }
      }
      auto m = blank_marker(header);
      m.id = static_cast<std::int32_t>(markers_.size());
      m.type = kTriangleList;
      m.action = kAdd;
      m.pose = pose_in_metres(part.T_world_part);  // the mesh is in the part frame
      m.color = colour(result.kind);
      const auto count = static_cast<std::uint32_t>(points.size());
      m.points = {count, count, points.data(), false};
      markers_.push_back(m);
    }
  }
  const auto n = static_cast<std::uint32_t>(markers_.size());
  msg_.markers = {n, n, markers_.data(), false};
}

}  // namespace rangefit::daemon
