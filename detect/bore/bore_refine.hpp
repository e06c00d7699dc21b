#pragma once
// Beyond the thesis: the final geometric least-squares fit of one bore wall, on the points near
// the RSF cylinder (not only those whose normal passed eq. 4.6), below the entrance plane and
// above a blind bore's bottom. Cost-bounded: iterated on a spread sample of the band, then
// polished on the full-resolution inliers, up to a point budget (see BoreOptions).

#include <Eigen/Core>
#include <memory_resource>
#include <span>

#include "detect/bore/bore_options.hpp"
#include "detect/bore/bore_region.hpp"
#include "detect/bore/cylinder_lsf.hpp"
#include "detect/common/pca.hpp"

namespace rangefit {

// What the refinement starts from: the wall as segmented and the fitted entrance plane.
struct RefineInput {
  std::span<const Eigen::Vector3d> cloud;  // the whole scan the region was read from
  const BoreRegion* region = nullptr;
  std::span<const Eigen::Vector3d> wall, bottom;  // segmented wall and blind-bottom points
  pca::Plane plane;
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();  // plane normal toward the sensor
  double normal_radius = 0.0;                     // R of the normals, mm
  std::pmr::memory_resource* mr = std::pmr::get_default_resource();  // the fit's buffers
};

struct RefineOutcome {
  CylinderLsfResult lsf;
  std::size_t inliers = 0;  // points of the last fit
  CylinderSigma sigma;      // of the last fit on its inliers (invalid: too few points)
};

RefineOutcome refine_wall(const RefineInput& in, const Cylinder& start, const BoreOptions& o);

}  // namespace rangefit
