#pragma once
// Scan surface that carries on past a posed part's flat faces: evidence that the part was fitted
// to a piece of a larger object (a cylinder posed on one end of a longer can, a box on part of a
// longer or wider one). Beyond the thesis: M, I and S (eq. 5.2-5.4) and the coverage
// (object_coverage.hpp) look only at the part's own surface, and a part posed inside a longer
// look-alike covers all of it and is empty inside. What tells them apart is that the scan goes
// on where the part ends: the look-alike's side wall continues straight past the part's cap, or
// its top face past the part's edge, within the few tens of per cent a look-alike differs by.
// It carries on from the face: a neighbour standing level with the part a few millimetres beyond
// it, across a bare strip, is no continuation.
//
// Only faces that are straight along the direction they are extended in are asked (side walls
// along the axis for eps1 <= 0.5, flat caps outwards, flat sides of a box-like part): a rounded
// surface curves away past its end, and a bigger ball is the size evidence's job
// (object_hypotheses.hpp size_evidence). Tapered parts are not asked.

#include <Eigen/Geometry>
#include <optional>
#include <span>

#include "detect/common/kdtree.hpp"
#include "detect/common/pca.hpp"
#include "detect/object/superquadric.hpp"

namespace rangefit {

struct ContinuationOptions {
  // Faces are extended by this share of the part's size, or farther where the band would leave
  // less than two bands between a point past the face and the extension's own rounded end.
  double reach = 0.25;
  double band_mm = 1.0;  // a point is on a surface within this distance (the scan's noise)
  // Points this close to the removed table (its normal towards the objects) are not asked: the
  // table continues every bottom face.
  std::optional<pca::Plane> table;
  double table_margin_mm = 5.0;
  std::size_t max_points = 6000;  // even subsample of the neighbourhood
};

struct Continuation {
  int surface = 0;     // points on the part's surface (within band_mm)
  // Points outside it, on one of its flat faces extended past its edge, of the faces whose
  // surface runs on to them from the edge with no gap wider than two point spacings (or band_mm).
  int continuing = 0;
  // continuing / surface: the share of the part's own evidence that carries on past it (0 with
  // no surface points or a part that is not asked).
  double share = 0.0;
};

// `explained`: parts of the same object (with their poses) whose points are not asked (a shaft's
// end runs into its head).
struct PlacedShape {
  Superquadric shape;
  Eigen::Isometry3d T_world_part = Eigen::Isometry3d::Identity();
};
Continuation surface_continuation(const Superquadric& sq, const Eigen::Isometry3d& T_world_part,
                                  std::span<const Eigen::Vector3d> points, const KdTree& tree,
                                  const ContinuationOptions& options = {},
                                  std::span<const PlacedShape> explained = {});

}  // namespace rangefit
