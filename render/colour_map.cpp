#include "render/colour_map.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace rangefit::render {
namespace {

template <std::size_t N>
Rgb piecewise(const std::array<Rgb, N>& stops, double t) {
  if (!std::isfinite(t)) t = 0.0;
  const double x = std::clamp(t, 0.0, 1.0) * (N - 1);
  const auto i = std::min(static_cast<std::size_t>(x), N - 2);
  const double f = x - static_cast<double>(i);
  const auto mix = [f](std::uint8_t a, std::uint8_t b) {
    return static_cast<std::uint8_t>(std::lround(a + f * (b - a)));
  };
  return {mix(stops[i].r, stops[i + 1].r), mix(stops[i].g, stops[i + 1].g),
          mix(stops[i].b, stops[i + 1].b)};
}

}  // namespace

Rgb height_colour(double t) {
  // viridis at 0, 0.25, 0.5, 0.75, 1
  static constexpr std::array<Rgb, 5> kStops{
      {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}}};
  return piecewise(kStops, t);
}

Rgb distance_colour(double t) {
  static constexpr std::array<Rgb, 3> kStops{{{40, 200, 80}, {240, 220, 40}, {230, 40, 30}}};
  return piecewise(kStops, t);
}

}  // namespace rangefit::render
