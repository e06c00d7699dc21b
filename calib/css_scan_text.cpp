#include "calib/css_scan_text.hpp"

#include <cmath>
#include <cstdio>

#include "calib/stripe_calibration.hpp"
#include "calib/text_fields.hpp"
#include "hal/rpy.hpp"

namespace rangefit::calib {

using text_fields::number;
using text_fields::words;

Eigen::Isometry3d pose_from_xyz_rpy(const double v[6]) {
  return hal::pose_xyz_rpy(v[0], v[1], v[2], v[3], v[4], v[5]);
}

void xyz_rpy_of(const Eigen::Isometry3d& T, double v[6]) {
  const Eigen::Vector3d rpy = rpy_of(T.linear(), Eigen::Vector3d::Zero());
  for (int i = 0; i < 3; ++i) {
    v[i] = T.translation()[i];
    v[3 + i] = rpy[i];
  }
}

CssScansParse parse_css_scans(std::string_view text, std::string_view source) {
  CssScansParse out;
  std::vector<CssSphereScan> scans;
  const auto header = [](const std::vector<std::string_view>& w) -> std::string {
    if (w.size() != 2 || w[0] != "rangefit-css-sphere-scans" || w[1] != "1") {
      return "expected the header 'rangefit-css-sphere-scans 1'";
    }
    return {};
  };
  const auto record = [&](const std::vector<std::string_view>& w) -> std::string {
    if (w[0] == "pose") {
      double v[6];
      bool ok = w.size() == 7;
      for (std::size_t i = 0; ok && i < 6; ++i) ok = number(w[i + 1], v[i]);
      if (!ok) return "expected 'pose X_MM Y_MM Z_MM ROLL PITCH YAW' (rad)";
      scans.push_back({pose_from_xyz_rpy(v), {}});
      return {};
    }
    CssSample s;
    if (w.size() != 3 || !number(w[0], s.omega_rad) || !number(w[1], s.beam_rad) ||
        !number(w[2], s.range_mm)) {
      return "expected 'OMEGA_RAD BEAM_RAD RANGE_MM' or 'pose ...'";
    }
    if (scans.empty()) return "a sample before the first 'pose ...' line";
    if (!(s.range_mm > 0.0)) return "the range must be positive";
    scans.back().samples.push_back(s);
    return {};
  };
  out.error = text_fields::read_lines(text, source, "empty scan file (no header)", header, record);
  if (out.error.empty()) out.scans = std::move(scans);
  return out;
}

std::string format_css_scans(const std::vector<CssSphereScan>& scans) {
  std::string out = "rangefit-css-sphere-scans 1\n";
  char buf[160];
  for (const CssSphereScan& scan : scans) {
    double v[6];
    xyz_rpy_of(scan.T_base_joint, v);
    std::snprintf(buf, sizeof buf, "pose %.17g %.17g %.17g %.17g %.17g %.17g\n", v[0], v[1], v[2],
                  v[3], v[4], v[5]);
    out += buf;
    for (const CssSample& s : scan.samples) {
      std::snprintf(buf, sizeof buf, "%.12g %.12g %.12g\n", s.omega_rad, s.beam_rad, s.range_mm);
      out += buf;
    }
  }
  return out;
}

}  // namespace rangefit::calib
