#include "daemon/service/scan_types.hpp"

namespace rangefit::daemon {

const char* to_string(DetectKind k) {
  switch (k) {
    case DetectKind::kBore:
      return "bore";
    case DetectKind::kObject:
      return "object";
    case DetectKind::kLearn:
      return "learn";
    case DetectKind::kCalibrate:
      return "calibrate";
  }
  return "bore";
}

bool kind_from_string(const std::string& name, DetectKind* kind) {
  for (const DetectKind k :
       {DetectKind::kBore, DetectKind::kObject, DetectKind::kLearn, DetectKind::kCalibrate}) {
    if (name == to_string(k)) {
      *kind = k;
      return true;
    }
  }
  return false;
}

void convert_sweep_units(ScanRequest& req, bool linear_sweep, bool to_wire) {
  if (!linear_sweep) return;
  const double f = to_wire ? kMetresPerMm : 1.0 / kMetresPerMm;
  req.sweep_start *= f;
  req.sweep_end *= f;
  req.sweep_speed *= f;
}

}  // namespace rangefit::daemon
