#pragma once
// Checks for numeric command-line options. CLI11's Range lets NaN through (every comparison with
// NaN is false) and nothing bounds a coordinate, so `--normal-keep nan` was accepted and
// `--sensor-position 1e308,0,0` ended deep in the detector in "cannot create std::vector larger
// than max_size()".

#include <CLI/CLI.hpp>

#include <cmath>
#include <sstream>
#include <string>

namespace rangefit::cli {

// Every position or direction on the command line, mm: 1 km is far beyond any cell.
inline constexpr double kMaxCoordinateMm = 1e6;

// A finite number in [lo, hi].
inline CLI::Validator finite_range(double lo, double hi) {
  std::ostringstream range;
  range << "[" << lo << ", " << hi << "]";
  const std::string description = "FINITE in " + range.str();
  return CLI::Validator(
      [lo, hi, description](std::string& text) -> std::string {
        double v = 0.0;
        if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v) || v < lo || v > hi) {
          return "value " + text + " is not a finite number in " + description.substr(10);
        }
        return {};
      },
      description);
}

}  // namespace rangefit::cli
