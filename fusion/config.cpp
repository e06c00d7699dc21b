// TOML -> FusionConfig. Each table is read through a Fields reader that knows its dotted path,
// so every error names the field; keys nobody reads are reported as unknown.
#include "fusion/config.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <sstream>
#include <stdexcept>

#include "io/toml_file.hpp"

namespace rangefit::fusion {
namespace {

// line: where the field (or, when it is missing, its table) stands in the file; 0 = unknown.
struct FieldError : std::runtime_error {
  FieldError(const std::string& what, std::uint32_t at_line)
      : std::runtime_error(what), line(at_line) {}
  std::uint32_t line;
};

constexpr double kBig = 1e9;
constexpr double kPi = std::numbers::pi;

class Fields {
 public:
  Fields(const toml::table* table, std::string path) : table_(table), path_(std::move(path)) {}

  [[noreturn]] void fail(std::string_view key, const std::string& why) const {
    const toml::node* n = table_ == nullptr ? nullptr : table_->get(key);
    const std::uint32_t line = n != nullptr        ? n->source().begin.line
                               : table_ != nullptr ? table_->source().begin.line
                                                   : 0;
    throw FieldError(path_ + "." + std::string(key) + ": " + why, line);
  }
  void read(std::string_view key, double& out, double lo, double hi) {
    const toml::node* n = find(key);
    if (n == nullptr) return;
    const std::optional<double> v = n->value<double>();  // integers convert too
    if (!v || n->is_boolean() || n->is_string()) fail(key, "must be a number");
    if (!std::isfinite(*v) || *v < lo || *v > hi) fail(key, "must be in " + range(lo, hi, *v));
    out = *v;
  }
  template <class Int>
  void read_int(std::string_view key, Int& out, std::int64_t lo, std::int64_t hi) {
    const toml::node* n = find(key);
    if (n == nullptr) return;
    if (!n->is_integer()) fail(key, "must be an integer");
    const std::int64_t v = n->as_integer()->get();
    if (v < lo || v > hi) {
      fail(key, "must be in " + range(static_cast<double>(lo), static_cast<double>(hi),
                                      static_cast<double>(v)));
    }
    out = static_cast<Int>(v);
  }
  void read_ms(std::string_view key, hal::Duration& out, double lo, double hi) {
    double ms = static_cast<double>(out.count()) * 1e-6;
    read(key, ms, lo, hi);
    out = hal::Duration(std::llround(ms * 1e6));
  }
  void read(std::string_view key, Eigen::Vector3d& out, double lo, double hi) {
    const toml::node* n = find(key);
    if (n == nullptr) return;
    const toml::array* a = n->as_array();
    if (a == nullptr || a->size() != 3) fail(key, "must be an array of 3 numbers");
    for (int i = 0; i < 3; ++i) {
      const std::optional<double> v = (*a)[static_cast<std::size_t>(i)].value<double>();
      if (!v || !std::isfinite(*v) || *v < lo || *v > hi) {
        fail(key, "element " + std::to_string(i) + " must be a number in " + range(lo, hi));
      }
      out[i] = *v;
    }
  }
  void read(std::string_view key, std::string& out) {
    const toml::node* n = find(key);
    if (n == nullptr) return;
    if (!n->is_string()) fail(key, "must be a string");
    out = n->as_string()->get();
  }
  const toml::table* sub_table(std::string_view key) {
    const toml::node* n = find(key);
    if (n == nullptr) return nullptr;
    if (!n->is_table()) fail(key, "must be a table");
    return n->as_table();
  }
  std::string path(std::string_view key) const { return path_ + "." + std::string(key); }
  // Call after reading: any key not read is a typo or a field this version does not know.
  void reject_unknown() const {
    if (table_ == nullptr) return;
    for (const auto& [k, v] : *table_) {
      if (!used_.contains(std::string(k.str()))) fail(k.str(), "unknown field");
    }
  }

 private:
  const toml::node* find(std::string_view key) {
    used_.insert(std::string(key));
    return table_ == nullptr ? nullptr : table_->get(key);
  }
  static std::string range(double lo, double hi, std::optional<double> got = {}) {
    std::ostringstream s;
    s << "[" << lo << ", " << hi << "]";
    if (got) s << ", got " << *got;
    return s.str();
  }
  const toml::table* table_;
  std::string path_;
  std::set<std::string> used_;
};

void read_time(Fields& f, TimeLimits& t) {
  f.read_ms("max_reference_gap_ms", t.max_reference_gap, 0.001, 1e6);
  f.read_ms("clock_jump_tolerance_ms", t.clock_jump_tolerance, 0.0, 1e6);
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
  f.read_ms("nominal_period_ms", c.nominal_period, 0.1, 1e5);
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
  Fields f(parent.sub_table("ranger"), parent.path("ranger"));
  f.read_int("points_per_profile", r.points_per_profile, 2, 1 << 16);
  f.read("fan_angle_rad", r.fan_angle_rad, 1e-6, kPi);
  f.read("min_depth_mm", r.min_depth_mm, 0.0, kBig);
  f.read("max_depth_mm", r.max_depth_mm, 0.0, kBig);
  if (r.max_depth_mm <= r.min_depth_mm) f.fail("max_depth_mm", "must exceed min_depth_mm");
  f.read("baseline_mm", r.baseline_mm, 0.0, kBig);
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
  f.read_ms("profile_period_ms", c.profile_period, 0.0, 1e5);
  f.read_int("expected_profiles", c.expected_profiles, 1, 10000000);
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
  f.read_ms("profile_period_ms", c.profile_period, 0.0, 1e5);
  f.read_int("expected_profiles", c.expected_profiles, 1, 10000000);
  f.reject_unknown();
}

FusionConfig read_fusion(const toml::table& table) {
  FusionConfig c;
  Fields f(&table, "fusion");
  {
    Fields sub(f.sub_table("time"), "fusion.time");
    read_time(sub, c.css.limits);
    c.stripe_cell.limits = c.pan_tilt.limits = c.css.limits;
  }
  {
    Fields sub(f.sub_table("css"), "fusion.css");
    read_css(sub, c.css);
  }
  {
    Fields sub(f.sub_table("stripe_cell"), "fusion.stripe_cell");
    read_stripe_cell(sub, c.stripe_cell);
  }
  {
    Fields sub(f.sub_table("pan_tilt"), "fusion.pan_tilt");
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
    result.config = read_fusion(fusion_table);
  } catch (const FieldError& e) {
    result.error = std::string(source_name) +
                   (e.line > 0 ? ":" + std::to_string(e.line) : std::string()) + ": " + e.what();
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
