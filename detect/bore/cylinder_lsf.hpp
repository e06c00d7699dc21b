#pragma once
// Geometric least-squares cylinder fit (LSF): minimises the point-to-surface distances
// |P_perp (q - c)| - r over the axis point, direction and radius. Used two ways: as the thesis's
// comparison baseline (steepest descent for 200 iterations from a PCA or CAD start, 4.2.4) and,
// beyond the thesis, as the final Levenberg-Marquardt refinement of the RSF result with a Huber
// loss so the remaining outliers do not pull the fit.

#include <Eigen/Core>
#include <span>

#include "detect/bore/cylinder_rsf.hpp"

namespace rangefit {

enum class LsfMethod { kLevenbergMarquardt, kSteepestDescent };

struct CylinderLsfOptions {
  LsfMethod method = LsfMethod::kLevenbergMarquardt;
  int max_iterations = 30;    // thesis baseline: 200 steepest-descent iterations
  double huber_delta = 0.15;  // mm; residuals beyond count linearly; 0: plain least squares
  double tolerance = 1e-9;    // stop when the relative cost decrease falls below this
  // Beyond: stop when no point of the surface moves more than this (mm) in a step (axis shift,
  // tilt times the data's axial half-length, radius change); 0: off.
  double step_tolerance = 0.0;
  // Beyond: Gauss-Newton steps taken without checking the cost (up to max_iterations, ending
  // early on the step tolerance), and no rms: the polish of a fit that starts near the minimum
  // of a sample of the same points (one pass over the points per step instead of three).
  bool single_unchecked_step = false;
  // Beyond: > 0, points whose residual is beyond this (mm) get no weight in a step, so a
  // trimmed fit selects its inliers again around every new estimate (a trim made once around
  // a start that is off biases the fit toward that start); 0: every point counts.
  double trim = 0.0;
};

struct CylinderLsfResult {
  bool converged = false;
  int iterations = 0;
  Cylinder cylinder;
  double rms = 0.0;  // rms residual of all points at the end, mm
};

// Fits from `initial` (its axis must be non-zero, radius > 0). Empty input returns initial,
// not converged.
CylinderLsfResult fit_cylinder_lsf(std::span<const Eigen::Vector3d> points, const Cylinder& initial,
                                   const CylinderLsfOptions& options);

// One-sigma standard errors of the cylinder c fitted to `points` (those whose residual is within
// `trim` when > 0): sigma^2 (J^T J)^-1 of plain least squares at c, sigma^2 the residuals'
// variance over n - 5. Under independent noise of that size this is the Cramer-Rao bound of any
// unbiased estimate from these points: how well the data determine the cylinder, not how far
// the fit is from the truth (a bias, e.g. from a wrong model, does not show).
struct CylinderSigma {
  bool valid = false;
  double axis = 0.0;    // rad: rms angle of the axis error (both tilt components)
  double offset = 0.0;  // mm: rms shift of the axis across itself at the points' centroid
  double radius = 0.0;  // mm
  double rms = 0.0;     // rms residual, mm
  std::size_t points = 0;
};
CylinderSigma cylinder_sigma(std::span<const Eigen::Vector3d> points, const Cylinder& c,
                             double trim);

// The thesis's PCA start for the LSF baseline: centroid, largest eigenvector, given radius.
Cylinder cylinder_from_pca(std::span<const Eigen::Vector3d> points, double radius);

}  // namespace rangefit
