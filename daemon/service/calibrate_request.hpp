#pragma once
// kind = calibrate: the cell's extrinsics from the scan of a calibration body it just took
// (thesis 3.2), as `rangefit calibrate` does from recorded raw sweeps. The result is never
// applied: the calibrated configuration fields (calibration_<target>.toml) and a report of
// residuals and uncertainties go into the spool entry, and the result's details say where; the
// operator reviews them and includes them in the configuration.
//
// target "stripe": the hollow cube on the stripe cell's table. The service gets the fused scan,
// not the ranger's raw profiles; fusion mapped every profile point q at axis position s to
// p = T_cell_ranger q - s d with the configured geometry, which is invertible: s is where p
// pierces the configured laser plane, q = T_cell_ranger^-1 (p + s d). The configured geometry
// is the calibration's start, as in the CLI's --config.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "calib/stripe_calibration.hpp"
#include "daemon/service/scan_sensor.hpp"
#include "daemon/service/scan_types.hpp"
#include "detect/common/point_cloud.hpp"
#include "hal/samples.hpp"

namespace rangefit::daemon {

// "[x, y, z]" as a TOML array, 10 digits.
std::string toml_vec(const Eigen::Vector3d& v);

// Reasons of a calibration that ran but was not supported by the scan start with this.
inline constexpr std::string_view kNotCalibrated = "not calibrated: ";

// The scan's points in the frame fusion built them in (sensor.T_scan_fusion undone): where a
// calibration takes them back to the sensor's raw samples.
PointCloud in_fusion_frame(const PointCloud& cloud, const ScanSensor& sensor);

struct RawStripeProfiles {
  std::vector<hal::RangerProfile> profiles;  // one per grid row, NaN where the row has no point
  std::vector<double> axis_mm;               // per profile: the mean axis position of its points
  std::string error;                         // why not, when the scan cannot be taken back
};

// The profiles of a fused stripe scan (organised: one grid row per profile), points in the
// fusion (cell table) frame, taken back through geometry g.
RawStripeProfiles raw_stripe_profiles(const PointCloud& cloud_in_cell,
                                      const hal::StripeCellGeometry& g);

// The [fusion.stripe_cell] fields of the result, and the report beside them.
std::string stripe_calibration_toml(const calib::StripeCalibrationResult& r,
                                    const std::string& source);
std::string stripe_calibration_report(const calib::StripeCalibrationResult& r,
                                      const hal::StripeCellGeometry& start,
                                      const std::string& source);

DetectionResult calibrate_request(const PointCloud& cloud, const ScanRequest& request,
                                  const ScanSensor& sensor, std::uint64_t default_seed);

}  // namespace rangefit::daemon
