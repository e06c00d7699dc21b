#pragma once
// rangefitd's results as ROS 2 perception and visualisation tools read them:
// vision_msgs/Detection3DArray (rt/rangefit/detections3d: one detection per part, hypothesis =
// model name and score, pose = the part's pose as on rt/rangefit/poses and rt/tf, box = the
// part's extent) and visualization_msgs/MarkerArray (rt/rangefit/markers: a DELETEALL of our
// namespace, then one TRIANGLE_LIST mesh per part, so rviz2 shows what was found and nothing
// older). SI metres, frames from [frames], stamps = acquisition time. Like messages.hpp, each
// *Out owns the storage its C struct points into.

#include <map>
#include <string>
#include <vector>

#include "daemon/dds/part_surface.hpp"
#include "daemon/service/scan_types.hpp"
#include "detect/object/object_model.hpp"
#include "vision_msgs.h"
#include "visualization_msgs.h"

namespace rangefit::daemon {

// The marker namespace (Marker.ns) of every mesh rangefitd draws.
inline constexpr const char* kMarkerNamespace = "rangefit";

class Detection3DArrayOut {
 public:
  // part_frame_prefix: put before each part's frame name in Detection3D.id (the ROS namespace).
  Detection3DArrayOut(const DetectionResult& result, std::string frame,
                      const std::map<std::string, ObjectModel>& models,
                      const std::string& part_frame_prefix = "");
  Detection3DArrayOut(const Detection3DArrayOut&) = delete;
  Detection3DArrayOut& operator=(const Detection3DArrayOut&) = delete;
  const vision_msgs_msg_dds__Detection3DArray_& msg() const { return msg_; }

 private:
  std::string frame_, class_id_;
  std::vector<std::string> ids_;
  std::vector<vision_msgs_msg_dds__ObjectHypothesisWithPose_> hypotheses_;
  std::vector<vision_msgs_msg_dds__Detection3D_> detections_;
  vision_msgs_msg_dds__Detection3DArray_ msg_{};
};

class MarkerArrayOut {
 public:
  MarkerArrayOut(const DetectionResult& result, std::string frame,
                 const std::map<std::string, ObjectModel>& models);
  MarkerArrayOut(const MarkerArrayOut&) = delete;
  MarkerArrayOut& operator=(const MarkerArrayOut&) = delete;
  const visualization_msgs_msg_dds__MarkerArray_& msg() const { return msg_; }

 private:
  std::string frame_;
  std::vector<std::vector<geometry_msgs_msg_dds__Point_>> points_;
  std::vector<visualization_msgs_msg_dds__Marker_> markers_;
  visualization_msgs_msg_dds__MarkerArray_ msg_{};
};

}  // namespace rangefit::daemon
