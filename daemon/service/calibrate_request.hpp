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
// is the calibration's start, as in the CLI's --config. The sweep is written to the spool entry
// as raw_sweep_stripe.txt, the file `rangefit calibrate stripe --scans` reads.
//
// Several cameras of one laser plane (the stripe devices [[fusion.stripe_cell.cameras]] names,
// besides the first) calibrate together, solved as one rig (calib/stripe_calibration.hpp), and
// the result holds every camera's fields. One request may name them all (`sensors`): on one axis
// they sweep the cube together, the axis moving once, and each camera's sweep is spooled
// (raw_sweep_file). Or each sweeps in a request of its own, and the last names the earlier ones
// in `scans`; the two ways combine.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "calib/raw_sweep_text.hpp"
#include "calib/stripe_calibration.hpp"
#include "daemon/service/calibration_records.hpp"
#include "daemon/service/pipeline.hpp"
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

// One camera of a stripe calibration: the stripe device's name in [[fusion.stripe_cell.cameras]],
// or empty for the cell's first camera ([fusion.stripe_cell] itself); its configured layout.
struct StripeCameraStart {
  std::string name;
  hal::StripeCellGeometry start;
};

// The [fusion.stripe_cell] fields of the result (the first camera's pose when it took part, and
// the axis) and a [[fusion.stripe_cell.cameras]] entry per further camera; the report beside
// them. cameras: one per camera of r, in its order.
std::string stripe_calibration_toml(const calib::StripeRigResult& r,
                                    std::span<const StripeCameraStart> cameras,
                                    const std::string& source);
std::string stripe_calibration_report(const calib::StripeRigResult& r,
                                      std::span<const StripeCameraStart> cameras,
                                      const std::string& source);

// What a stripe calibrate request keeps for a later one that names it: the camera's sweep, its
// configured layout and the cube it swept.
struct StripeCalibrationSweep {
  std::string sensor;
  StripeCameraStart camera;
  calib::RawSweep sweep;
  CalibrationTarget target;
};
// A request's sweeps: one per camera it named.
using StripeCalibrationSweeps = CalibrationRecords<std::vector<StripeCalibrationSweep>>;

// The spool file of a request's sweep with its k-th camera (from 0): raw_sweep_stripe.txt for the
// first, raw_sweep_stripe_<k + 1>.txt for the others.
std::string raw_sweep_file(std::size_t k);

// views: each camera's scan apart when the request named several (sensors); empty: the scan
// (cloud, sensor) is request.sensor's.
DetectionResult calibrate_request(const PointCloud& cloud, const ScanRequest& request,
                                  const ScanSensor& sensor, std::span<const SensorScan> views,
                                  StripeCalibrationSweeps& sweeps, std::uint64_t default_seed);

}  // namespace rangefit::daemon
