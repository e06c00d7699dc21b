#pragma once
// Fusion's configuration: extrinsics, sensor constants and time-alignment limits, read from
// TOML at start-up so that a change never needs a rebuild. Every field is optional; the default
// is the thesis value (CSS: eq. 4.17-4.21, sensor cell and head: 5.2.1) or, where the thesis
// gives none, the documented placeholder of hal/stripe_geometry.hpp and hal/pan_tilt_geometry.hpp.
// Unknown keys are errors (a typo must not fall back to a default silently). Layout, with the
// defaults (angles rad, lengths mm, times ms; docs/frames.md names every frame):
//
//   [fusion.time]         max_reference_gap_ms = 50, clock_jump_tolerance_ms = 2,
//                         max_pending_frames = 4, max_faults = 10
//   [fusion.css]          omega_source = "joint" | "stamps", joint = 6, omega_zero_rad = 0,
//                         deflection_rad = 0.0872665 (5 deg), scan_speed_mm_s = 2,
//                         nominal_period_ms = 142.857 (7 Hz), expected_revolutions = 180,
//                         standoff_mm = 88.5, scan_diameter_mm = 27, laser_ccd_distance_mm = 27,
//                         phase_rad = 0, min_range_mm = 65, max_range_mm = 130,
//                         eta_rad = 0.502655 (28.8 deg), pivot_radius_mm = 285.8
//   [fusion.stripe_cell]  ranger_position_cell_mm = [0, 200, 600],
//                         ranger_rpy_cell_rad = [3.14159, 0, 0], axis_direction_cell = [0, 1, 0],
//                         axis_travel_mm = 400, max_speed_mm_s = 6.3, profile_period_ms = 0,
//                         expected_profiles = 8192
//   [[fusion.stripe_cell.cameras]]  further cameras of the same laser plane (thesis fig. 3.6b):
//                         name (the stripe device's), ranger_position_cell_mm,
//                         ranger_rpy_cell_rad, baseline_mm (< 0: the other side); all required
//   [fusion.stripe_cell.ranger]  points_per_profile = 512, fan_angle_rad = 0.523599 (30 deg),
//                         min_depth_mm = 250, max_depth_mm = 650, baseline_mm = 300 (< 0: camera on
//                         the other side of the laser plane),
//                         camera_angle_rad = 1.047198 (60 deg)
//   [fusion.pan_tilt]     t_s_mm = [0, 0, 0], t_w_mm = [0, 0, 0], pan_zero_rad = 0,
//                         tilt_zero_rad = 0, sweep_angle_rad = 0.872665 (50 deg),
//                         sweep_rate_rad_s = 0.174533 (10 deg/s), profile_rate_hz = 100,
//                         profile_period_ms = 10, expected_profiles = 512
//   [[fusion.pan_tilt.cameras]]  further cameras of the head's laser plane: name (the pan_tilt
//                         device's), baseline_mm (< 0: the other side); both required
//   [fusion.pan_tilt.ranger]  as above, defaults min_depth_mm = 344, max_depth_mm = 2685,
//                         baseline_mm = 425 (thesis: A1, A2, B of the mobile head)
//
// [fusion.time] applies to all three assemblers.

#include <toml++/toml.h>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "fusion/css_assembler.hpp"
#include "fusion/profile_assembler.hpp"

namespace rangefit::fusion {

struct FusionConfig {
  CssFusionConfig css;
  StripeCellFusionConfig stripe_cell;
  PanTiltFusionConfig pan_tilt;
};

struct FusionConfigResult {
  std::optional<FusionConfig> config;  // set when valid
  std::string error;                   // "<source>: fusion.<table>.<field>: <problem>" when not
};

// Reads the contents of a [fusion] table (e.g. the daemon passes root["fusion"]).
FusionConfigResult parse_fusion_config(const toml::table& fusion_table,
                                       std::string_view source_name = "config");
// Parses a TOML document and reads its [fusion] table; a document without one gives the
// defaults. Other top-level tables are left to their owners.
FusionConfigResult parse_fusion_config(std::string_view toml_text,
                                       std::string_view source_name = "config");
FusionConfigResult load_fusion_config(const std::filesystem::path& path);

}  // namespace rangefit::fusion
