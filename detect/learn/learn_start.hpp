#pragma once
// Starting guesses for the model-learning fit (thesis 5.1.2: start from the moments). The part
// frame's axes come from the central moments of the object's points; when the object stood on a
// removed plane, the plane closes its hidden underside: one axis is the plane normal, the other
// two the moments of the points projected onto the plane, and the part reaches from the plane
// to the highest point. Each frame is tried with z along each of its axes and with a few
// shapes (ellipsoid, cylinder-like, box-like), because a single view can fit several of them
// locally and only the fit tells which one explains the points best.

#include <Eigen/Core>
#include <optional>
#include <span>
#include <vector>

#include "detect/learn/learn_fit.hpp"
#include "detect/common/pca.hpp"

namespace rangefit {

struct StartShape {
  double eps1 = 1.0, eps2 = 1.0;
  // Taper of the start (kx = ky). Only tried with z along the normal of the plane the object
  // stands on, narrowing upwards for taper < 0 (a cone, a bottle); elsewhere no sign is
  // preferred and the fit starts untapered.
  double taper = 0.0;
};

// `plane` (when valid) is the surface the object rests on; `shapes` the eps pairs to try.
std::vector<PosedSuperquadric> learn_starts(std::span<const Eigen::Vector3d> points,
                                            const std::optional<pca::Plane>& plane,
                                            std::span<const StartShape> shapes);

}  // namespace rangefit
