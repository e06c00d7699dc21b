#include "calib/raw_sweep_text.hpp"

#include <cmath>
#include <cstdio>

#include "calib/text_fields.hpp"

namespace rangefit::calib {
using text_fields::number;
using text_fields::words;

RawSweepParse parse_raw_sweep(std::string_view text, std::string_view source) {
  RawSweepParse out;
  RawSweep sweep;
  const auto header = [&](const std::vector<std::string_view>& w) -> std::string {
    double n = 0.0;
    if (w.size() != 4 || w[0] != "rangefit-raw-sweep" || w[1] != "1" ||
        (w[2] != "stripe" && w[2] != "pantilt") || !number(w[3], n) || n < 2 || n > 65536 ||
        n != std::floor(n)) {
      return "expected the header 'rangefit-raw-sweep 1 stripe|pantilt POINTS'";
    }
    sweep.kind = w[2] == "stripe" ? SweepKind::kStripe : SweepKind::kPanTilt;
    sweep.points_per_profile = static_cast<int>(n);
    return {};
  };
  const auto record = [&](const std::vector<std::string_view>& w) -> std::string {
    const auto n = static_cast<std::size_t>(sweep.points_per_profile);
    if (w[0] == "p") {
      hal::RangerProfile p;
      p.sequence = static_cast<std::uint32_t>(sweep.profiles.size());
      p.x_mm.assign(n, hal::kNoReturn);
      p.z_mm.assign(n, hal::kNoReturn);
      if (sweep.kind == SweepKind::kStripe) {
        double a = 0.0;
        if (w.size() != 2 || !number(w[1], a)) return "expected 'p AXIS_MM'";
        sweep.axis_mm.push_back(a);
      } else {
        hal::PanTiltSample s;
        if (w.size() != 3 || !number(w[1], s.pan_rad) || !number(w[2], s.tilt_rad)) {
          return "expected 'p PAN_RAD TILT_RAD'";
        }
        sweep.angles.push_back(s);
      }
      sweep.profiles.push_back(std::move(p));
      return {};
    }
    double k = 0.0, x = 0.0, z = 0.0;
    if (w.size() != 3 || !number(w[0], k) || !number(w[1], x) || !number(w[2], z)) {
      return "expected 'K X_MM Z_MM' or 'p ...'";
    }
    if (sweep.profiles.empty()) return "a point before the first profile line 'p ...'";
    if (k < 0 || k >= static_cast<double>(n) || k != std::floor(k)) {
      return "point index outside 0.." + std::to_string(n - 1);
    }
    auto& p = sweep.profiles.back();
    p.x_mm[static_cast<std::size_t>(k)] = static_cast<float>(x);
    p.z_mm[static_cast<std::size_t>(k)] = static_cast<float>(z);
    return {};
  };
  out.error = text_fields::read_lines(text, source, "empty sweep file (no header)", header, record);
  if (out.error.empty()) out.sweep = std::move(sweep);
  return out;
}

std::string format_raw_sweep(const RawSweep& sweep) {
  std::string out = "rangefit-raw-sweep 1 ";
  out += sweep.kind == SweepKind::kStripe ? "stripe " : "pantilt ";
  out += std::to_string(sweep.points_per_profile) + "\n";
  char buf[96];
  for (std::size_t r = 0; r < sweep.profiles.size(); ++r) {
    if (sweep.kind == SweepKind::kStripe) {
      std::snprintf(buf, sizeof buf, "p %.9g\n", sweep.axis_mm[r]);
    } else {
      std::snprintf(buf, sizeof buf, "p %.12g %.12g\n", sweep.angles[r].pan_rad,
                    sweep.angles[r].tilt_rad);
    }
    out += buf;
    const auto& p = sweep.profiles[r];
    for (std::size_t k = 0; k < p.z_mm.size() && k < p.x_mm.size(); ++k) {
      if (!std::isfinite(p.z_mm[k]) || !std::isfinite(p.x_mm[k])) continue;
      std::snprintf(buf, sizeof buf, "%zu %.9g %.9g\n", k, static_cast<double>(p.x_mm[k]),
                    static_cast<double>(p.z_mm[k]));
      out += buf;
    }
  }
  return out;
}

}  // namespace rangefit::calib
