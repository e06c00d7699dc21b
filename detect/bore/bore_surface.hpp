#pragma once
// Beyond the thesis (its chapter 7 names conical and elliptic bores as future work): bore walls
// that are not circular cylinders, and their geometric least-squares fit. A cone narrowing with
// depth (a 90 deg countersink: half-angle 45 deg; a tapered hole: a few degrees), optionally
// ending in a cylindrical bore, and an elliptic cylinder. The fit runs the project's one
// Levenberg-Marquardt loop (detect/levenberg_marquardt.hpp) over the pose and the shape, with
// the entrance held on the fitted entrance plane: a cone's radius is defined there, so its
// position along the axis is not free.

#include <Eigen/Core>
#include <span>

namespace rangefit {

// A bore wall in the frame of its entrance.
struct BoreSurface {
  bool cone = true;                                    // else an elliptic cylinder
  Eigen::Vector3d entrance = Eigen::Vector3d::Zero();  // axis meets the entrance plane, mm
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();     // unit, out of the bore
  Eigen::Vector3d major = Eigen::Vector3d::UnitX();    // unit, across the axis (ellipse: radius)
  double radius = 0.0;           // cone: at the entrance; ellipse: semi-axis along major, mm
  double radius2 = 0.0;          // ellipse: the semi-axis across major, mm
  double half_angle = 0.0;       // cone, rad
  double cylinder_radius = 0.0;  // cone: > 0, the cylinder it ends in (a countersink), mm
};

// Signed distance of p from the wall, > 0 in the material, mm. Cone: exact for the cone's
// generator line; a countersink's solid is outside both the cone and the cylinder, so its
// distance is the smaller of the two. Ellipse: radial distance (within 0.2 % of the normal one
// at an axis ratio of 0.9).
double surface_residual(const BoreSurface& s, const Eigen::Vector3d& p);

// Unit direction in which that residual grows at p: the wall's normal into the material at the
// wall point nearest p (the cylinder's where a countersink's cylinder is nearer).
Eigen::Vector3d surface_normal(const BoreSurface& s, const Eigen::Vector3d& p);

struct SurfaceFitOptions {
  int max_iterations = 100;
  double huber_delta = 0.15;     // mm; residuals beyond count linearly
  double step_tolerance = 1e-7;  // relative, eq. 2.64
};

struct SurfaceFitResult {
  BoreSurface surface;
  int iterations = 0;
  std::size_t inliers = 0;  // points that counted at the end
  double rms = 0.0;         // their rms residual, mm
  // One-sigma standard errors, sigma^2 (J^T W J)^-1: entrance (in the plane, mm), axis (rad),
  // radius, radius2, cylinder radius (mm), half-angle, major axis direction (rad).
  double sigma_entrance = 0.0, sigma_axis = 0.0, sigma_radius = 0.0, sigma_radius2 = 0.0;
  double sigma_cylinder_radius = 0.0, sigma_half_angle = 0.0, sigma_major = 0.0;
};

// plane_normal: of the entrance plane the entrance stays on. An empty span returns the start.
SurfaceFitResult fit_bore_surface(std::span<const Eigen::Vector3d> points, const BoreSurface& start,
                                  const Eigen::Vector3d& plane_normal,
                                  const SurfaceFitOptions& options);

}  // namespace rangefit
