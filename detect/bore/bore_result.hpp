#pragma once
// Output of the bore detection: found or why not, the pose, and counts and times per stage.

#include <Eigen/Core>
#include <optional>
#include <string_view>

namespace rangefit {

enum class BoreReason {
  kFound,
  kBadPrior,             // NaN/Inf or zero-length prior values, radius <= 0
  kEmptyRoi,             // no finite point within the region of interest
  kDegenerateNormals,    // no point passed the normal estimation (eq. 4.4)
  kNoPlane,              // too few plane points, or they do not define a plane
  kTooFewWallPoints,     // too few wall points after segmentation or the notch filter
  kFitFailed,            // the cylinder fit found no axis or radius
  kAxisParallelToPlane,  // the fitted axis does not cross the fitted plane
  kBadShape,             // cone and ellipse at once, half-angle outside [0, 80 deg), bad radius2
  kShapeFitFailed,       // the cone/ellipse fit found too few points near the model or ran off
};
std::string_view to_string(BoreReason r);

struct BoreCounts {
  std::size_t input = 0;           // points in the cloud
  std::size_t non_finite = 0;      // NaN/Inf points skipped (among those read)
  std::size_t stride = 1;          // every stride-th scan point was read (a dense region)
  std::size_t roi = 0;             // points in the region of interest (read ones x stride)
  std::size_t normal_queries = 0;  // after sub-sampling
  std::size_t normals = 0;         // normals kept by eq. 4.4
  std::size_t plane = 0;           // plane points (eq. 4.5), before the robust refit
  std::size_t wall = 0;            // wall points (eq. 4.6)
  std::size_t wall_final = 0;      // wall points of the last cylinder fit
  std::size_t refine_inliers = 0;
  int axis_pairs = 0;  // RSF samples accepted (last fit)
  int triangles = 0;
};

// Milliseconds per stage (steady clock).
struct BoreTimes {
  double roi = 0, normals = 0, segmentation = 0, rsf = 0, refine = 0, entrance = 0, total = 0;
};

// The outer wall of a pipe when both walls were asked for (BoreWalls::kBoth).
struct BoreWallResult {
  bool found = false;
  BoreReason reason = BoreReason::kFitFailed;
  Eigen::Vector3d entrance = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double radius = 0.0;
  bool refined = false;
  std::size_t wall = 0, refine_inliers = 0;
};

// A cone or elliptic bore's shape as fitted (BorePrior::half_angle or radius2 set), with one-sigma
// standard errors from the fit's normal matrix (sigma^2 (J^T W J)^-1, sigma^2 from the inliers'
// residuals): they say how well the points determine a value, not how far it is from the truth.
struct BoreShape {
  bool cone = false;             // else an ellipse
  double half_angle = 0.0;       // cone, rad
  double cylinder_radius = 0.0;  // cone ending in a cylinder, mm (0: a pure cone)
  double radius2 = 0.0;          // ellipse: the semi-axis across major_axis, mm
  Eigen::Vector3d major_axis = Eigen::Vector3d::UnitX();  // ellipse: unit, direction of radius
  double sigma_radius = 0.0, sigma_half_angle = 0.0, sigma_cylinder_radius = 0.0;
  double sigma_radius2 = 0.0, sigma_major_axis = 0.0;  // mm, rad
  double sigma_entrance = 0.0, sigma_axis = 0.0;       // mm (in the plane), rad
  double rms = 0.0;                                    // inliers' rms residual, mm
  int iterations = 0;
  bool seeded_by_rsf = false;  // the start was the RSF cylinder of the wall (else the CAD axis)
};

struct BoreResult {
  bool found = false;
  BoreReason reason = BoreReason::kFitFailed;
  Eigen::Vector3d entrance = Eigen::Vector3d::Zero();  // axis meets the entrance plane, mm
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();     // unit, out of the bore toward the sensor
  double radius = 0.0;                                 // mm
  Eigen::Vector3d plane_normal = Eigen::Vector3d::UnitZ();  // fitted entrance plane, unit
  double rsf_radius = 0.0;                                  // radius before the refinement, mm
  Eigen::Vector3d rsf_axis = Eigen::Vector3d::UnitZ();
  bool second_fit = false;  // the notch filter removed points and the RSF ran again
  bool refined = false;     // the final least-squares refinement converged and was used
  // The refined cylinder's one-sigma standard errors from its own fit (cylinder_sigma in
  // cylinder_lsf.hpp: sigma^2 (J^T J)^-1 on the inliers, the Cramer-Rao bound of these points
  // under their residual noise): how well the scan determines the bore, e.g. a short one-sided
  // wall's axis; 0 when not refined.
  double sigma_axis = 0.0;    // rad, rms angle
  double sigma_offset = 0.0;  // mm, rms shift of the axis across itself at the wall's centroid
  double sigma_radius = 0.0;  // mm
  BoreCounts counts;
  BoreTimes time_ms;
  // walls = kBoth: the outer wall (the fields above are the inner one); otherwise empty.
  std::optional<BoreWallResult> outer;
  // A cone or elliptic bore: its shape (radius above is the cone's radius at the entrance, or the
  // ellipse's semi-axis along shape->major_axis); otherwise empty.
  std::optional<BoreShape> shape;
};

}  // namespace rangefit
