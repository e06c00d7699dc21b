#include "daemon/service/model_detector.hpp"

#include <algorithm>
#include <cmath>

#include "daemon/service/bore_fit_json.hpp"
#include "daemon/service/bore_shape_json.hpp"
#include "daemon/service/calibrate_css_request.hpp"
#include "daemon/service/calibrate_pan_tilt_request.hpp"
#include "daemon/service/calibrate_request.hpp"
#include "daemon/service/detection_adapter.hpp"
#include "daemon/service/learn_request.hpp"
#include "daemon/service/object_result_json.hpp"
#include "detect/bore/bore_detector.hpp"
#include "detect/object/object_detector.hpp"

namespace rangefit::daemon {

DetectionResult ModelDetector::detect(const PointCloud& cloud, const ScanRequest& request,
                                      const ScanSensor& sensor, std::span<const SensorScan> views) {
  const ScanSensor seen = with_request_sensor(sensor, request);
  switch (request.kind) {
    case DetectKind::kObject:
      return detect_object_request(cloud, request, seen);
    case DetectKind::kLearn:
      return learn_request(cloud, request, config_.detection.seed);
    case DetectKind::kCalibrate:
      if (request.target.kind == "css") {
        return calibrate_css_request(cloud, request, seen, css_poses_);
      }
      if (request.target.kind == "pantilt") {
        return calibrate_pan_tilt_request(cloud, request, seen, pan_tilt_sweeps_,
                                          config_.detection.seed);
      }
      return calibrate_request(cloud, request, seen, views, stripe_sweeps_, config_.detection.seed);
    case DetectKind::kBore:
      break;
  }
  return detect_bore_request(cloud, request, seen);
}

namespace {

// Pose of a bore or pipe wall: origin at the entrance, z along the axis (out of the bore); score:
// agreement of the fitted radius with the prior (informative; found is the detector's).
PartPose wall_pose(const char* name, const Eigen::Vector3d& entrance, const Eigen::Vector3d& axis,
                   double radius, double prior_radius) {
  PartPose part;
  part.name = name;
  part.T_world_part.linear() =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis).toRotationMatrix();
  part.T_world_part.translation() = entrance;
  const double error = std::abs(radius - prior_radius);
  part.score = std::max(0.0, 1.0 - error / std::max(prior_radius, 1e-9));
  return part;
}

}  // namespace

DetectionResult ModelDetector::detect_bore_request(const PointCloud& cloud,
                                                   const ScanRequest& request,
                                                   const ScanSensor& sensor) {
  const BoreDetection d = bore_detection(bore_query(request, config_.detection.seed), sensor);
  const BoreResult r = detect_bore(cloud, d.prior, d.options, bore_workspace_);
  DetectionResult out;
  out.found = r.found;
  if (!r.found) {
    out.reason = std::string(to_string(r.reason));
    return out;
  }
  out.bore_radius_mm = r.radius;
  // walls = outer: the one wall fitted is the outer one, against the outer radius.
  const bool outer_only = d.options.walls == BoreWalls::kOuter && d.prior.outer_radius > 0.0;
  out.parts.push_back(wall_pose(outer_only ? "outer" : "bore", r.entrance, r.axis, r.radius,
                                outer_only ? d.prior.outer_radius : d.prior.radius));
  out.details = bore_fit_json(r);
  out.details["walls"] = request.bore.walls.empty() ? "inner" : request.bore.walls;
  if (r.shape) out.details["shape"] = bore_shape_json(*r.shape);
  if (r.outer) {
    // Both walls: the outer one as a second part when found, and its radius in the details.
    nlohmann::json o = {{"found", r.outer->found}, {"wall_points", r.outer->wall}};
    if (r.outer->found) {
      o["radius_mm"] = r.outer->radius;
      o["entrance_mm"] = {r.outer->entrance.x(), r.outer->entrance.y(), r.outer->entrance.z()};
      o["axis"] = {r.outer->axis.x(), r.outer->axis.y(), r.outer->axis.z()};
      out.parts.push_back(wall_pose("outer", r.outer->entrance, r.outer->axis, r.outer->radius,
                                    d.prior.outer_radius));
    } else {
      o["reason"] = std::string(to_string(r.outer->reason));
    }
    out.details["outer"] = o;
  }
  return out;
}

DetectionResult ModelDetector::detect_object_request(const PointCloud& cloud,
                                                     const ScanRequest& request,
                                                     const ScanSensor& sensor) {
  const ObjectModelConfig* cfg = config_.object(request.model);
  if (cfg == nullptr) return DetectionResult::error(request, "unknown model " + request.model);
  ScanSensor seen = sensor;
  if (seen.view.kind == SensorView::Kind::kUnknown) seen.view = cloud.sensor;  // e.g. a replay
  // The viewpoint the request gives (as `rangefit object --viewpoint`) enables the free-space
  // check; a view direction alone says nothing an object detector uses.
  const ObjectDetectOptions options =
      object_detect_options(object_query(request, config_.detection.seed), cfg->model, seen);
  const ObjectDetectResult r = detect_object(cfg->model, cloud.points, options);
  DetectionResult out;
  out.found = r.found();
  // What `rangefit object --json` says beyond the poses: scores, and when not found which check
  // each candidate failed and by how much.
  out.details = object_result_json(cfg->model, r);
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
