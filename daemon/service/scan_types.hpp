#pragma once
// What flows through rangefitd: a scan request in, a detection result out. Internal units are
// mm and rad (the DDS layer converts to and from SI metres at the wire, see messages.hpp).

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace rangefit::daemon {

// bore, object: find it; learn: teach an object model from the scan (thesis ch. 6); calibrate:
// the sensor's extrinsics from a scan of a calibration body (thesis 3.2), written, never applied.
enum class DetectKind { kBore, kObject, kLearn, kCalibrate };
const char* to_string(DetectKind k);
// The kind of that name; false when there is none.
bool kind_from_string(const std::string& name, DetectKind* kind);
inline constexpr const char* kKindNames = "\"bore\", \"object\", \"learn\" or \"calibrate\"";

struct BorePrior {                                        // from CAD
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();  // a point on the bore axis, world
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();        // bore axis direction, world
  double radius_mm = 0.0;                                 // nominal radius
  // Normal of the surface around the bore, world; none: the axis (a perpendicular bore).
  std::optional<Eigen::Vector3d> plane_normal;
  // A thick-walled pipe (as `rangefit bore --cad-outer-radius --walls`): its outer wall radius,
  // mm (0: none) and which wall to fit: "inner" (the bore; also empty), "outer" or "both".
  double outer_radius_mm = 0.0;
  std::string walls;
  double normal_keep = 0.0;  // share (0..1] of region points that get a normal; 0: all
  // A cone or elliptic bore (as `rangefit bore --cad-half-angle --cad-cylinder-radius
  // --cad-radius2 --cad-major-axis`, DDS, the ROS 2 service and JSON); 0 / none: a circular
  // cylinder.
  double half_angle_rad = 0.0;                // cone half-angle
  double cylinder_radius_mm = 0.0;            // the cylinder a countersink's cone ends in
  double radius2_mm = 0.0;                    // the ellipse's semi-axis across major_axis
  std::optional<Eigen::Vector3d> major_axis;  // the direction of radius_mm, world
};

// A calibration body for kind = calibrate: "stripe", the hollow six-plane cube on the stripe
// cell's table, scanned once (as `rangefit calibrate stripe --cube --cube-pose`); "pantilt", the
// same cube before the pan-tilt head, one pan sweep per request at the tilt the cell program
// holds (as `rangefit calibrate pantilt`); or "css", a precision sphere the CSS scans at several
// robot poses, one request per pose (as `rangefit calibrate css --sphere-radius`). A pantilt or
// css request records its sweep or pose, and one that names earlier ones in `scans` (at least 2
// tilts, 3 robot poses in all) also solves.
struct CalibrationTarget {
  std::string kind;        // "stripe", "pantilt" or "css"
  double edge_mm = 120.0;  // stripe, pantilt: cube edge
  double bar_mm = 12.0;    // stripe, pantilt: bar thickness
  // stripe: where the fixture holds the cube on the table; pantilt: in the head's world frame.
  Eigen::Isometry3d T_table_target = Eigen::Isometry3d::Identity();
  // pantilt: the tilt the cell program holds the head at for this sweep, as the head reports it
  // (rad); the service checks the head's report against it. Unset: whatever the head reports.
  std::optional<double> tilt_rad;
  double radius_mm = 0.0;  // css: the sphere's certified radius
  // css: the last joint's frame in the robot base at this scan, as the robot controller reports
  // it (the robot program moved the robot there; the daemon does not read it).
  std::optional<Eigen::Isometry3d> T_base_joint;
  // pantilt, css: ids of earlier requests of the same target whose sweeps or poses join this one.
  std::vector<std::string> scans;
};

struct ScanRequest {
  std::string id;
  DetectKind kind = DetectKind::kBore;
  std::string model;       // object model name (kind = object)
  BorePrior bore;          // kind = bore
  std::string sensor;      // device name; empty = the configured default for the kind
  double sweep_start = 0;  // sweep axis: mm (linear sensors) or rad (rotary); start == end: default
  double sweep_end = 0;
  double sweep_speed = 0;  // per second, same unit; 0 = device default
  // Detector overrides (0: the detector's defaults, the configured seed).
  int instances = 1;       // K object instances wanted, best first (kind = object)
  int hypotheses = 0;      // m pose hypotheses per part (kind = object)
  int trials = 0;          // n RANSAC trials per hypothesis (kind = object)
  std::uint64_t seed = 0;  // seed of the detector's random sampling
  // What the user knows of the sensor (as `rangefit bore --view-dir --sensor-position` and
  // `rangefit object --viewpoint`), in the world frame; each replaces what the scan's sensor
  // reports. A position is preferred over a direction.
  std::optional<Eigen::Vector3d> view_dir;         // unit, from the scene toward the sensor
  std::optional<Eigen::Vector3d> sensor_position;  // mm
  int parts = 0;                                   // kind = learn: 1 or 2 parts; 0: 1
  // kind = learn: the sensors whose scans are fused before learning (each over its configured
  // sweep; their clouds all in the world frame), e.g. the stripe cell's sweep and the pan-tilt
  // head's, so the hidden side of one view is seen by another. Empty: `sensor` alone.
  std::vector<std::string> sensors;
  CalibrationTarget target;                        // kind = calibrate
};

struct PartPose {
  std::string name;
  Eigen::Isometry3d T_world_part = Eigen::Isometry3d::Identity();  // translation in mm
  double score = 0.0;                                              // 0..1, higher is better
  std::uint32_t instance = 0;  // which detected instance the part belongs to (0: the best)
};

struct DetectionResult {
  std::string request_id;
  DetectKind kind = DetectKind::kBore;
  std::string model;
  bool found = false;
  std::string reason;  // empty when found
  std::vector<PartPose> parts;
  double bore_radius_mm = 0.0;
  std::size_t num_points = 0;
  double scan_seconds = 0.0;
  double detect_seconds = 0.0;
  std::string spool_entry;  // empty when the scan was not spooled (e.g. rejected request)
  // When the scan's last sample was taken, wall clock (ns since the Unix epoch); 0: unknown.
  std::int64_t acquired_wall_ns = 0;
  // What a kind reports beyond poses (JSON, mm and rad): a pipe's outer wall, the learnt model
  // and its residuals, the calibration and its residuals, and "files": where in the spool entry
  // the files below were written. Null when there is nothing.
  nlohmann::json details;
  // Files the spool writes into the entry beside the cloud (name, content), e.g. model.toml.
  std::vector<std::pair<std::string, std::string>> files;

  static DetectionResult error(const ScanRequest& req, std::string why) {
    DetectionResult r;
    r.request_id = req.id;
    r.kind = req.kind;
    r.model = req.model;
    r.reason = std::move(why);
    return r;
  }
};

constexpr double kMetresPerMm = 1e-3;  // SI metres on the DDS wire

// The wire carries sweep positions in metres for linear sensors (SensorKind::sweep_linear);
// internally they are mm.
void convert_sweep_units(ScanRequest& req, bool linear_sweep, bool to_wire);

}  // namespace rangefit::daemon
