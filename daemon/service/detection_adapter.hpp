#pragma once
// The one door from a request to detect/: (query, model, sensor) -> detector options, used by
// `rangefit bore|object` and by rangefitd alike, so whatever detect/ can do is reachable from
// both or from neither. The query is what the user asked (CAD prior, counts, seed); the sensor
// is what the scan's sensor knows (daemon/scan_sensor.hpp), given on the command line offline.

#include <cstdint>
#include <optional>

#include "daemon/service/scan_sensor.hpp"
#include "daemon/service/scan_types.hpp"
#include "detect/bore/bore_options.hpp"
#include "detect/object/object_detector.hpp"

namespace rangefit::daemon {

struct BoreQuery {
  Eigen::Vector3d entrance = Eigen::Vector3d::Zero();  // mm
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double radius = 0.0;        // mm
  double outer_radius = 0.0;  // mm, for walls kOuter and kBoth
  BoreWalls walls = BoreWalls::kInner;
  std::optional<Eigen::Vector3d> plane_normal;  // none: the axis
  // A cone or elliptic bore (detect/bore_options.hpp BorePrior): the cone's half-angle, rad, and
  // the cylinder it ends in, mm; the ellipse's second semi-axis, mm, and the direction of the
  // first (radius). 0 / none: a circular cylinder.
  double half_angle = 0.0;
  double cylinder_radius = 0.0;
  double radius2 = 0.0;
  std::optional<Eigen::Vector3d> major_axis;
  double normal_keep = 1.0;
  std::uint64_t seed = 1;
};

struct ObjectQuery {
  int hypotheses = 0;  // 0: the detector's defaults (per single and per compound part)
  int trials = 0;      // 0: the detector's default
  int instances = 1;   // K
  std::uint64_t seed = 1;
};

struct BoreDetection {
  rangefit::BorePrior prior;
  BoreOptions options;
};

BoreDetection bore_detection(const BoreQuery& query, const ScanSensor& sensor);
// model: the model the options are for (counts apply per part of a compound model).
ObjectDetectOptions object_detect_options(const ObjectQuery& query, const ObjectModel& model,
                                          const ScanSensor& sensor);

// What the scan's sensor knows, with what the request says it knows instead: a view direction
// or sensor position given in the request replaces the sensor's (offline, the CLI's options fill
// an empty ScanSensor the same way).
ScanSensor with_request_sensor(const ScanSensor& sensor, const ScanRequest& request);

// The queries a service request carries; seed 0 in the request: default_seed (the config's).
BoreQuery bore_query(const ScanRequest& request, std::uint64_t default_seed);
ObjectQuery object_query(const ScanRequest& request, std::uint64_t default_seed);

}  // namespace rangefit::daemon
