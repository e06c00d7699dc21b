#include "daemon/dds/ros_frames.hpp"

#include "daemon/dds/dds_chars.hpp"
#include "daemon/dds/messages.hpp"

namespace rangefit::daemon {

geometry_msgs_msg_dds__Pose_ pose_in_metres(const Eigen::Isometry3d& T) {
  const Eigen::Vector3d t = T.translation() * kMetresPerMm;
  const Eigen::Quaterniond q(T.rotation());
  return {{t.x(), t.y(), t.z()}, {q.x(), q.y(), q.z(), q.w()}};
}

std::string part_frame(const DetectionResult& result, const PartPose& part) {
  const std::string what = result.kind == DetectKind::kBore ? "bore" : result.model;
  return "rangefit/" + what + "/" + (part.name.empty() ? "part" : part.name) + "/" +
         std::to_string(part.instance);
}

std::vector<NamedTransform> part_frames(const DetectionResult& result, const std::string& prefix) {
  std::vector<NamedTransform> out;
  if (!result.found) return out;
  for (const auto& part : result.parts)
    out.push_back({prefix + part_frame(result, part), part.T_world_part});
  return out;
}

builtin_interfaces_msg_dds__Time_ result_stamp(const DetectionResult& result) {
  return result.acquired_wall_ns > 0 ? wall_time(result.acquired_wall_ns) : wall_time_now();
}

TfOut::TfOut(const builtin_interfaces_msg_dds__Time_& stamp, std::string parent,
             std::vector<NamedTransform> transforms)
    : parent_(std::move(parent)), named_(std::move(transforms)) {
  for (const auto& n : named_) {
    const auto pose = pose_in_metres(n.T_parent_child);
    geometry_msgs_msg_dds__TransformStamped_ t{};
    t.header = {stamp, dds_chars(parent_)};
    t.child_frame_id = dds_chars(n.child_frame);
    t.transform.translation = {pose.position.x, pose.position.y, pose.position.z};
    t.transform.rotation = pose.orientation;
    transforms_.push_back(t);
  }
  const auto n = static_cast<std::uint32_t>(transforms_.size());
  msg_.transforms = {n, n, transforms_.data(), false};
}

PoseArrayOut::PoseArrayOut(const DetectionResult& result, std::string frame)
    : frame_(std::move(frame)) {
  for (const auto& part : result.parts) poses_.push_back(pose_in_metres(part.T_world_part));
  const auto n = static_cast<std::uint32_t>(poses_.size());
  msg_.header = {result_stamp(result), dds_chars(frame_)};
  msg_.poses = {n, n, poses_.data(), false};
}

}  // namespace rangefit::daemon
