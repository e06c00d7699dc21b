// TOML -> FusionConfig through io::TomlFields: every error names file, line and field; keys nobody
// reads are reported as unknown.
#include "fusion/config.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <sstream>
#include <stdexcept>

#include "io/toml_fields.hpp"
#include "io/toml_file.hpp"

namespace rangefit::fusion {
namespace {

constexpr double kBig = 1e9;
constexpr double kPi = std::numbers::pi;

using Fields = io::TomlFields;

void read_ms(Fields& f, std::string_view key, hal::Duration& out, double lo, double hi) {
  double ms = static_cast<double>(out.count()) * 1e-6;
  f.read(key, ms, lo, hi);
  out = hal::Duration(std::llround(ms * 1e6));
}

void read_time(Fields& f, TimeLimits& t) {
  read_ms(f, "max_reference_gap_ms", t.max_reference_gap, 0.001, 1e6);
  read_ms(f, "clock_jump_tolerance_ms", t.clock_jump_tolerance, 0.0, 1e6);
  f.read_int("max_pending_frames", t.max_pending_frames, 0, 100000);
  f.read_int("max_faults", t.max_faults, 0, 1000000000);
  f.reject_unknown();
}

void read_css(Fields& f, CssFusionConfig& c) {
  std::string source = c.omega_source == OmegaSource::kJointStream ? "joint" : "stamps";
  f.read("omega_source", source);
  if (source == "joint") {
    c.omega_source = OmegaSource::kJointStream;
  } else if (source == "stamps") {
    c.omega_source = OmegaSource::kStartEndStamps;
  } else {
    f.fail("omega_source", "must be \"joint\" or \"stamps\", got \"" + source + "\"");
  }
  f.read_int("joint", c.joint, 0, 255);
  f.read("omega_zero_rad", c.omega_zero_rad, -2 * kPi, 2 * kPi);
  f.read("deflection_rad", c.deflection_rad, 1e-6, kPi / 2);
  f.read("scan_speed_mm_s", c.scan_speed_mm_s, 1e-6, 1e4);
  read_ms(f, "nominal_period_ms", c.nominal_period, 0.1, 1e5);
  f.read_int("expected_revolutions", c.expected_revolutions, 1, 100000);
  hal::CssGeometry& g = c.geometry;
  f.read("standoff_mm", g.standoff_mm, 1e-3, kBig);
  f.read("scan_diameter_mm", g.scan_diameter_mm, 1e-3, kBig);
  f.read("laser_ccd_distance_mm", g.laser_ccd_distance_mm, 0.0, kBig);
  f.read("phase_rad", g.phase_rad, -2 * kPi, 2 * kPi);
  f.read("min_range_mm", g.min_range_mm, 0.0, kBig);
  f.read("max_range_mm", g.max_range_mm, 0.0, kBig);
  if (g.max_range_mm <= g.min_range_mm) f.fail("max_range_mm", "must exceed min_range_mm");
  f.read("eta_rad", g.eta_rad, -kPi, kPi);
  f.read("pivot_radius_mm", g.pivot_radius_mm, 1e-3, kBig);
  f.reject_unknown();
}

void read_ranger(Fields& parent, hal::StripeRanger& r) {
  Fields f = parent.sub("ranger");
  f.read_int("points_per_profile", r.points_per_profile, 2, 1 << 16);
  f.read("fan_angle_rad", r.fan_angle_rad, 1e-6, kPi);
  f.read("min_depth_mm", r.min_depth_mm, 0.0, kBig);
  f.read("max_depth_mm", r.max_depth_mm, 0.0, kBig);
  if (r.max_depth_mm <= r.min_depth_mm) f.fail("max_depth_mm", "must exceed min_depth_mm");
  f.read("baseline_mm", r.baseline_mm, -kBig, kBig);
  f.read("camera_angle_rad", r.camera_angle_rad, 0.0, kPi);
  f.reject_unknown();
}

void read_stripe_cell(Fields& f, StripeCellFusionConfig& c) {
  hal::StripeCellGeometry& g = c.geometry;
  read_ranger(f, g.ranger);
  f.read("ranger_position_cell_mm", g.ranger_position_cell_mm, -kBig, kBig);
  f.read("ranger_rpy_cell_rad", g.ranger_rpy_cell_rad, -2 * kPi, 2 * kPi);
  f.read("axis_direction_cell", g.axis_direction_cell, -1.0, 1.0);
  if (std::abs(g.axis_direction_cell.norm() - 1.0) > 1e-6) {
    f.fail("axis_direction_cell", "must be a unit vector");
  }
  f.read("axis_travel_mm", g.axis_travel_mm, 0.0, kBig);
  f.read("max_speed_mm_s", g.max_speed_mm_s, 0.0, kBig);
  read_ms(f, "profile_period_ms", c.profile_period, 0.0, 1e5);
  f.read_int("expected_profiles", c.expected_profiles, 1, 10000000);
  if (const toml::array* cams = f.table_array("cameras")) {
    for (std::size_t i = 0; i < cams->size(); ++i) {
      Fields e = f.element("cameras", *cams, i);
      StripeCameraConfig cam;
      for (const char* key :
           {"name", "ranger_position_cell_mm", "ranger_rpy_cell_rad", "baseline_mm"}) {
        e.require(key);
      }
      e.read("name", cam.name);
      if (cam.name.empty()) e.fail("name", "must not be empty");
      for (const StripeCameraConfig& other : c.cameras) {
        if (other.name == cam.name) e.fail("name", "\"" + cam.name + "\" is given twice");
      }
      e.read("ranger_position_cell_mm", cam.ranger_position_cell_mm, -kBig, kBig);
      e.read("ranger_rpy_cell_rad", cam.ranger_rpy_cell_rad, -2 * kPi, 2 * kPi);
      e.read("baseline_mm", cam.baseline_mm, -kBig, kBig);
      e.reject_unknown();
      c.cameras.push_back(std::move(cam));
    }
  }
  f.reject_unknown();
}

void read_pan_tilt(Fields& f, PanTiltFusionConfig& c) {
  hal::PanTiltGeometry& g = c.geometry;
  read_ranger(f, g.ranger);
  f.read("t_s_mm", g.t_s_mm, -kBig, kBig);
  f.read("t_w_mm", g.t_w_mm, -kBig, kBig);
  f.read("pan_zero_rad", g.pan_zero_rad, -2 * kPi, 2 * kPi);
  f.read("tilt_zero_rad", g.tilt_zero_rad, -2 * kPi, 2 * kPi);
  f.read("sweep_angle_rad", g.sweep_angle_rad, 0.0, 2 * kPi);
  f.read("sweep_rate_rad_s", g.sweep_rate_rad_s, 0.0, 100.0);
  f.read("profile_rate_hz", g.profile_rate_hz, 1e-3, 1e6);
  read_ms(f, "profile_period_ms", c.profile_period, 0.0, 1e5);
  f.read_int("expected_profiles", c.expected_profiles, 1, 10000000);
  if (const toml::array* cams = f.table_array("cameras")) {
    for (std::size_t i = 0; i < cams->size(); ++i) {
      Fields e = f.element("cameras", *cams, i);
      PanTiltCameraConfig cam;
      for (const char* key : {"name", "baseline_mm"}) e.require(key);
      e.read("name", cam.name);
      if (cam.name.empty()) e.fail("name", "must not be empty");
      for (const PanTiltCameraConfig& other : c.cameras) {
        if (other.name == cam.name) e.fail("name", "\"" + cam.name + "\" is given twice");
      }
      e.read("baseline_mm", cam.baseline_mm, -kBig, kBig);
      if (cam.baseline_mm == 0.0) e.fail("baseline_mm", "a camera in the laser plane sees nothing");
      e.reject_unknown();
      c.cameras.push_back(std::move(cam));
    }
  }
  f.reject_unknown();
}

FusionConfig read_fusion(const toml::table& table, std::string_view source) {
  FusionConfig c;
  Fields f(&table, std::string(source), "fusion");
  {
    Fields sub = f.sub("time");
    read_time(sub, c.css.limits);
    c.stripe_cell.limits = c.pan_tilt.limits = c.css.limits;
  }
  {
    Fields sub = f.sub("css");
    read_css(sub, c.css);
  }
  {
    Fields sub = f.sub("stripe_cell");
    read_stripe_cell(sub, c.stripe_cell);
  }
  {
    Fields sub = f.sub("pan_tilt");
    read_pan_tilt(sub, c.pan_tilt);
  }
  f.reject_unknown();
  return c;
}

}  // namespace

FusionConfigResult parse_fusion_config(const toml::table& fusion_table,
                                       std::string_view source_name) {
  FusionConfigResult result;
  try {
    result.config = read_fusion(fusion_table, source_name);
  } catch (const io::TomlError& e) {
    result.error = e.what();
  }
  return result;
}

FusionConfigResult parse_fusion_config(std::string_view toml_text, std::string_view source_name) {
  toml::table root;
  try {
    root = io::parse_toml(toml_text, source_name);
  } catch (const io::TomlError& e) {
    return {std::nullopt, e.what()};
  }
  const toml::node* fusion = root.get("fusion");
  if (fusion == nullptr) return {FusionConfig{}, {}};
  if (!fusion->is_table())
    return {std::nullopt, std::string(source_name) + ": fusion: must be a table"};
  return parse_fusion_config(*fusion->as_table(), source_name);
}

FusionConfigResult load_fusion_config(const std::filesystem::path& path) {
  try {
    return parse_fusion_config(io::read_toml_file(path), path.string());
  } catch (const io::TomlError& e) {
    return {std::nullopt, e.what()};
  }
}

}  // namespace rangefit::fusion
