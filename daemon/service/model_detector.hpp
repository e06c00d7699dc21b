#pragma once
// The Detector rangefitd and `rangefit replay` run with: the thesis detectors of detect/ with the
// options the detection adapter (daemon/service/detection_adapter.hpp) makes of the request, the
// configured model and what the scan's sensor knows; their found/reason are reported unchanged
// (no gate of its own).

#include "daemon/service/calibrate_css_request.hpp"
#include "daemon/service/calibrate_pan_tilt_request.hpp"
#include "daemon/service/calibrate_request.hpp"
#include "daemon/service/config.hpp"
#include "daemon/service/pipeline.hpp"
#include "detect/bore/bore_workspace.hpp"

namespace rangefit::daemon {

class ModelDetector final : public Detector {
 public:
  explicit ModelDetector(DetectorConfig config) : config_(std::move(config)) {}
  DetectionResult detect(const PointCloud& cloud, const ScanRequest& request,
                         const ScanSensor& sensor, std::span<const SensorScan> views) override;

 private:
  DetectionResult detect_object_request(const PointCloud& cloud, const ScanRequest& request,
                                        const ScanSensor& sensor);
  DetectionResult detect_bore_request(const PointCloud& cloud, const ScanRequest& request,
                                      const ScanSensor& sensor);
  DetectorConfig config_;
  // The bore pipeline's memory, kept between requests: a bore request like the one before
  // allocates nothing in the detector. One call at a time: the pipeline joins a detection before
  // it starts the next.
  BoreWorkspace bore_workspace_;
  // The robot poses and sweeps calibration requests recorded, for the requests that join them.
  CssCalibrationPoses css_poses_;
  PanTiltCalibrationSweeps pan_tilt_sweeps_;
  StripeCalibrationSweeps stripe_sweeps_;
};

}  // namespace rangefit::daemon
