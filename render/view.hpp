#pragma once
// An orthographic view of a scene: which way the viewer looks, which world point sits at the
// panel centre and how many pixels a millimetre spans. Orthographic on purpose: distances read
// off the picture are the same everywhere in it, and a bore seen along its axis stays a circle.

#include <Eigen/Core>
#include <span>

namespace rangefit::render {

struct OrthoView {
  // Orthonormal, right-handed: right x up = toward. `toward` points from the scene at the viewer.
  Eigen::Vector3d right = Eigen::Vector3d::UnitX();
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  Eigen::Vector3d toward = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // world point at the panel centre, mm
  double px_per_mm = 1.0;
  int width = 1;  // panel size, px
  int height = 1;

  // Pixel position in the panel (x right, y down; pixel centres at half-integers).
  Eigen::Vector2d project(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d d = p - centre;
    return {0.5 * width + px_per_mm * d.dot(right), 0.5 * height - px_per_mm * d.dot(up)};
  }
  // Larger is nearer the viewer, mm.
  double depth(const Eigen::Vector3d& p) const { return (p - centre).dot(toward); }
};

// A view looking along -toward (toward need not be unit, must be non-zero) with the image's up
// as close to up_hint as possible (any other up when the two are parallel).
OrthoView look_from(const Eigen::Vector3d& toward, const Eigen::Vector3d& up_hint);

// Sets centre and scale so the box spanned by `points` (in the view's right/up plane) fills the
// panel of width x height px, with `margin` (share of the panel) left free on each side. `trim`
// (share of the points at each end of each direction) lets a few outliers fall outside.
void fit_to(OrthoView& view, std::span<const Eigen::Vector3d> points, int width, int height,
            double margin = 0.06, double trim = 0.0);

}  // namespace rangefit::render
