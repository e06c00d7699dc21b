#include "daemon/service/detection_adapter.hpp"

namespace rangefit::daemon {

BoreDetection bore_detection(const BoreQuery& q, const ScanSensor& sensor) {
  BoreDetection d;
  d.prior.entrance = q.entrance;
  d.prior.axis = q.axis;
  d.prior.radius = q.radius;
  d.prior.outer_radius = q.outer_radius;
  d.prior.half_angle = q.half_angle;
  d.prior.cylinder_radius = q.cylinder_radius;
  d.prior.radius2 = q.radius2;
  if (q.major_axis) d.prior.major_axis = *q.major_axis;
  d.options.walls = q.walls;
  d.prior.plane_normal = q.plane_normal;
  d.options.seed = q.seed;
  d.options.normal_keep = q.normal_keep;
  d.options.view_dir = sensor.view_dir;
  d.options.sensor_position = sensor.sensor_position;
  if (!d.options.view_dir && !d.options.sensor_position &&
      sensor.view.kind == SensorView::Kind::kPoint) {
    d.options.sensor_position = sensor.view.origin;
  }
  return d;
}

ObjectDetectOptions object_detect_options(const ObjectQuery& q, const ObjectModel& model,
                                          const ScanSensor& sensor) {
  ObjectDetectOptions o;
  if (q.hypotheses > 0) {
    if (model.parts.size() > 1) {
      o.compound_hypotheses = q.hypotheses;
    } else {
      o.hypotheses = q.hypotheses;
    }
  }
  if (q.trials > 0) o.trials = q.trials;
  o.instances = q.instances;
  o.seed = q.seed;
  o.threads = 0;  // all cores: results depend only on the seed (fixed batches)
  o.sensor = sensor.view;
  if (sensor.sensor_position) {
    o.viewpoint = sensor.sensor_position;
  } else if (sensor.view.kind == SensorView::Kind::kPoint) {
    o.viewpoint = sensor.view.origin;
  }
  return o;
}

ScanSensor with_request_sensor(const ScanSensor& sensor, const ScanRequest& r) {
  ScanSensor s = sensor;
  if (r.sensor_position) {
    s.sensor_position = r.sensor_position;
  } else if (r.view_dir) {
    s.view_dir = r.view_dir;
    s.sensor_position.reset();  // a position would be preferred over the direction given
  }
  return s;
}

BoreQuery bore_query(const ScanRequest& r, std::uint64_t default_seed) {
  BoreQuery q;
  q.entrance = r.bore.position_mm;
  q.axis = r.bore.axis;
  q.radius = r.bore.radius_mm;
  q.plane_normal = r.bore.plane_normal;
  q.outer_radius = r.bore.outer_radius_mm;
  q.half_angle = r.bore.half_angle_rad;
  q.cylinder_radius = r.bore.cylinder_radius_mm;
  q.radius2 = r.bore.radius2_mm;
  q.major_axis = r.bore.major_axis;
  if (r.bore.walls == "outer") q.walls = BoreWalls::kOuter;
  if (r.bore.walls == "both") q.walls = BoreWalls::kBoth;
  if (r.bore.normal_keep > 0.0) q.normal_keep = r.bore.normal_keep;
  q.seed = r.seed != 0 ? r.seed : default_seed;
  return q;
}

ObjectQuery object_query(const ScanRequest& r, std::uint64_t default_seed) {
  ObjectQuery q;
  q.hypotheses = r.hypotheses;
  q.trials = r.trials;
  q.instances = r.instances > 0 ? r.instances : 1;
  q.seed = r.seed != 0 ? r.seed : default_seed;
  return q;
}

}  // namespace rangefit::daemon
