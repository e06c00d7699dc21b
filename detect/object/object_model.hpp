#pragma once
// A known object as the detector sees it (thesis ch. 5): one or a few tapered superquadric parts
// and, for compound objects, the links between them (5.1.3: the angle between the two z-axes and
// the distance between the two centres, and beyond the thesis where each part's axis points
// relative to the other's centre). A plain value type; io/object_model_file reads it.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "detect/object/superquadric.hpp"

namespace rangefit {

struct ModelPart {
  std::string name;
  Superquadric shape;
};

struct PartLink {
  std::size_t first = 0;     // index into ObjectModel::parts
  std::size_t second = 0;    // index into ObjectModel::parts
  double angle_rad = 0.0;    // nominal angle alpha_k between the parts' z-axes (eq. 5.5)
  double distance_mm = 0.0;  // nominal distance d_k between the part centres (eq. 5.6)
  // Beyond eq. 5.5-5.6: the angle each part's z-axis makes with the line between the centres,
  // folded to [0, pi/2] (first, second). Angle and distance leave the second part free to sit
  // anywhere on a sphere around the first: a mallet's shaft 30 mm along its head's axis from its
  // middle, or a look-alike's shaft lying in line with the true one at the same distance, passes
  // them. The bearings fix where it sits (head 90 deg: the shaft's centre in the head's middle
  // plane; shaft 0 deg: its axis points at the head). Unset: not checked (older model files).
  std::optional<std::array<double, 2>> bearing_rad;

  // Unset, or both within [0, pi/2].
  bool bearings_valid() const {
    return !bearing_rad || std::all_of(bearing_rad->begin(), bearing_rad->end(), [](double b) {
      return b >= 0.0 && b <= std::numbers::pi / 2.0;
    });
  }
};

// The link two posed parts make (first at a, second at b): the angle between their z-axes and
// the bearings folded to [0, pi/2] (a part's axis has no sign), the distance between their
// centres; no bearings when the centres coincide. What model learning writes, and what the
// detector compares with the model's link.
inline PartLink measure_link(std::size_t first, std::size_t second, const Eigen::Isometry3d& a,
                             const Eigen::Isometry3d& b) {
  const auto axis_angle = [](const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    return std::acos(std::clamp(std::abs(u.normalized().dot(v.normalized())), 0.0, 1.0));
  };
  const Eigen::Vector3d line = b.translation() - a.translation();
  PartLink l{first, second, axis_angle(a.linear().col(2), b.linear().col(2)), line.norm(),
             std::nullopt};
  if (l.distance_mm > 0.0) {
    l.bearing_rad = std::array<double, 2>{axis_angle(a.linear().col(2), line),
                                          axis_angle(b.linear().col(2), line)};
  }
  return l;
}

struct ObjectModel {
  std::string name;
  std::vector<ModelPart> parts;
  std::vector<PartLink> links;
};

}  // namespace rangefit
