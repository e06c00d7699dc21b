#pragma once
// Bore-hole detection from a range scan and a CAD prior (thesis chapter 4): region of interest,
// PCA normals, Gaussian-image segmentation, sequential cylinder fit with the notch re-fit,
// entrance as the axis meeting the plane, and an optional least-squares refinement.
// Pure: no I/O, no exceptions for bad data (see BoreResult::reason); deterministic per seed;
// no threads. With a workspace kept between calls, a call on a scan like the one before
// allocates nothing (bore_workspace.hpp); the result is the same with or without one.

#include "detect/bore/bore_options.hpp"
#include "detect/bore/bore_result.hpp"
#include "detect/bore/bore_workspace.hpp"
#include "detect/common/point_cloud.hpp"

namespace rangefit {

BoreResult detect_bore(const PointCloud& cloud, const BorePrior& prior,
                       const BoreOptions& options = {});
BoreResult detect_bore(const PointCloud& cloud, const BorePrior& prior, const BoreOptions& options,
                       BoreWorkspace& workspace);

}  // namespace rangefit
