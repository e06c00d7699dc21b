#pragma once
// kind = calibrate, target "pantilt": t_s, t_w and the encoder zeros of the pan-tilt head
// (eq. 5.7, calib/pan_tilt_calibration.hpp) from pan sweeps over the hollow calibration cube at
// two or more tilts. The cell program holds the tilt; each request sweeps once at the tilt the
// head reports (checked against the request's tilt_rad when given) and records that sweep; a
// request that names earlier ones (scans: their ids) joins their sweeps to its own and, with two
// tilts or more, solves. Every request writes its sweep to its spool entry as
// raw_sweep_pantilt.txt (calib/raw_sweep_text.hpp), so `rangefit calibrate pantilt --scans`
// solves from the same files offline; a solved one writes calibration_pantilt.toml and its
// report, never applied.
//
// The service gets the fused scan, not the raw stream: fusion placed profile row r with the pan
// and tilt it interpolated at the profile's stamp (ScanSensor::row_poses) as
// p = T_world_ranger(pan, tilt) (x, 0, z), so (x, z) = the inverse pose applied to p.

#include <cstddef>
#include <string>

#include "calib/pan_tilt_calibration.hpp"
#include "calib/raw_sweep_text.hpp"
#include "daemon/service/calibration_records.hpp"
#include "daemon/service/scan_sensor.hpp"
#include "daemon/service/scan_types.hpp"
#include "detect/common/point_cloud.hpp"

namespace rangefit::daemon {

struct RawPanTiltSweep {
  calib::RawSweep sweep;  // kind kPanTilt: per profile the reported pan and tilt
  std::string error;      // why the scan cannot be taken back, when it cannot
};

// The sweep of a fused pan-tilt scan (organised, one grid row per profile), points in the
// fusion (head world) frame, taken back through the sensor's geometry and row poses.
RawPanTiltSweep raw_pan_tilt_sweep(const PointCloud& cloud_in_head, const ScanSensor& sensor);

// The sweeps earlier pantilt calibration requests recorded.
using PanTiltCalibrationSweeps = CalibrationRecords<calib::RawSweep>;

// The [fusion.pan_tilt] fields of the result, and the report beside them (also `rangefit
// calibrate pantilt`'s). start: the configured geometry.
std::string pan_tilt_calibration_toml(const calib::PanTiltCalibrationResult& r, std::size_t sweeps,
                                      const std::string& source);
std::string pan_tilt_calibration_report(const calib::PanTiltCalibrationResult& r,
                                        const hal::PanTiltGeometry& start, std::size_t sweeps,
                                        const std::string& source);

DetectionResult calibrate_pan_tilt_request(const PointCloud& cloud, const ScanRequest& request,
                                           const ScanSensor& sensor,
                                           PanTiltCalibrationSweeps& sweeps,
                                           std::uint64_t default_seed);

}  // namespace rangefit::daemon
