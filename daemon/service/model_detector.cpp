#include "daemon/service/model_detector.hpp"

#include <algorithm>
#include <cmath>

#include "daemon/service/detection_adapter.hpp"
#include "detect/bore_detector.hpp"
#include "detect/object_detector.hpp"

namespace rangefit::daemon {

DetectionResult ModelDetector::detect(const PointCloud& cloud, const ScanRequest& request,
                                      const ScanSensor& sensor) {
  if (request.kind == DetectKind::kObject) return detect_object_request(cloud, request, sensor);
  return detect_bore_request(cloud, request, sensor);
}

DetectionResult ModelDetector::detect_bore_request(const PointCloud& cloud,
                                                   const ScanRequest& request,
                                                   const ScanSensor& sensor) {
  const BoreDetection d = bore_detection(bore_query(request, config_.detection.seed), sensor);
  const BoreResult r = detect_bore(cloud, d.prior, d.options);
  DetectionResult out;
  out.found = r.found;
  if (!r.found) {
    out.reason = std::string(to_string(r.reason));
    return out;
  }
  out.bore_radius_mm = r.radius;
  // Pose of the bore: origin at the entrance, z along the axis (out of the bore).
  PartPose part;
  part.name = "bore";
  part.T_world_part.linear() =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), r.axis).toRotationMatrix();
  part.T_world_part.translation() = r.entrance;
  // Score: agreement of the fitted radius with the prior (informative; found is the detector's).
  const double error = std::abs(r.radius - d.prior.radius);
  part.score = std::max(0.0, 1.0 - error / std::max(d.prior.radius, 1e-9));
  out.parts.push_back(part);
  return out;
}

DetectionResult ModelDetector::detect_object_request(const PointCloud& cloud,
                                                     const ScanRequest& request,
                                                     const ScanSensor& sensor) {
  const ObjectModelConfig* cfg = config_.object(request.model);
  if (cfg == nullptr) return DetectionResult::error(request, "unknown model " + request.model);
  ScanSensor seen = sensor;
  if (seen.view.kind == SensorView::Kind::kUnknown) seen.view = cloud.sensor;  // e.g. a replay
  const ObjectDetectOptions options =
      object_detect_options(object_query(request, config_.detection.seed), cfg->model, seen);
  const ObjectDetectResult r = detect_object(cfg->model, cloud.points, options);
  DetectionResult out;
  out.found = r.found();
  if (!out.found) {
    out.reason = to_string(r.reason);
    return out;
  }
  // Every instance, best first, each with all its parts in model order. Score in 0..1: share
  // of the neighbourhood lying on the surface band (eq. 5.4 over 5.3 + 5.4).
  for (std::size_t i = 0; i < r.instances.size(); ++i) {
    for (const auto& part : r.instances[i].parts) {
      const double total = static_cast<double>(part.scores.interior + part.scores.surface);
      const double score = total > 0 ? static_cast<double>(part.scores.surface) / total : 0.0;
      out.parts.push_back({part.name, part.T_world_part, score, static_cast<std::uint32_t>(i)});
    }
  }
  return out;
}

}  // namespace rangefit::daemon
