#include "daemon/service/scan_types.hpp"

namespace rangefit::daemon {

const char* to_string(DetectKind k) { return k == DetectKind::kBore ? "bore" : "object"; }

void convert_sweep_units(ScanRequest& req, bool linear_sweep, bool to_wire) {
  if (!linear_sweep) return;
  const double f = to_wire ? kMetresPerMm : 1.0 / kMetresPerMm;
  req.sweep_start *= f;
  req.sweep_end *= f;
  req.sweep_speed *= f;
}

}  // namespace rangefit::daemon
