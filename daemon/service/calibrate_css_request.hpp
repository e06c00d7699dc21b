#pragma once
// kind = calibrate, target "css": the CSS mount on the robot's last joint and the joint's zero
// (calib/css_calibration.hpp, hand-eye) from a precision sphere scanned at several robot poses.
// The daemon does not move the robot: the robot program moves it to a pose, sends a request
// that says where the joint is (robot_pose) and the sphere's radius, and the service scans there
// and records that pose's samples. A request that names earlier ones (scans: their ids) joins
// their poses to its own; with 3 or more in all it solves. Every request writes its own pose's
// samples to its spool entry as css_sphere_scan.txt (calib/css_scan_text.hpp), so
// `rangefit calibrate css --scans` can solve from the same files offline; a solved one writes
// calibration_css.toml and its report, never applied.
//
// The service gets the fused scan, not the raw stream. Fusion made each point of revolution row
// r, sample column i as p = R_y(omega) (L + range b_i) (eq. 4.17-4.19, L the laser point and b_i
// the beam of sample i in the joint frame, both from the configured geometry), which is
// invertible: omega and range are the two unknowns of three equations, solved by Gauss-Newton
// from the neighbouring sample's answer. The reported joint angle is omega + the configured
// zero; the configured geometry is the calibration's start, as in the CLI's --config.

#include <cstddef>
#include <string>
#include <vector>

#include "calib/css_calibration.hpp"
#include "daemon/service/calibration_records.hpp"
#include "daemon/service/scan_sensor.hpp"
#include "daemon/service/scan_types.hpp"
#include "detect/common/point_cloud.hpp"

namespace rangefit::daemon {

struct CssRawSamples {
  std::vector<calib::CssSample> samples;
  std::string error;  // why the scan cannot be taken back, when it cannot
};

// The samples of a fused CSS scan (organised: one grid row per revolution, one column per
// sample), points in the fusion (joint) frame.
CssRawSamples css_raw_samples(const PointCloud& cloud_in_joint, const ScanSensor::CssFusion& css);

// The robot poses earlier css calibration requests recorded.
using CssCalibrationPoses = CalibrationRecords<calib::CssSphereScan>;

// The [fusion.css] fields of the result, and the report beside them (also `rangefit calibrate
// css`'s). start: the configured geometry; omega_zero_start: the configured zero.
std::string css_calibration_toml(const calib::CssCalibrationResult& r, std::size_t poses,
                                 const std::string& source);
std::string css_calibration_report(const calib::CssCalibrationResult& r,
                                   const hal::CssGeometry& start, double omega_zero_start,
                                   double radius_mm, std::size_t poses, const std::string& source);

DetectionResult calibrate_css_request(const PointCloud& cloud, const ScanRequest& request,
                                      const ScanSensor& sensor, CssCalibrationPoses& poses);

}  // namespace rangefit::daemon
