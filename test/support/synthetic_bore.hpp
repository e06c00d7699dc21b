#pragma once
// A simple, seeded synthetic bore-hole scan: an orthographic ray caster over a part made of a top
// surface (plane, gently curved or bumpy) with one bore (straight or slanted; sharp, chamfered or
// rounded entrance; optional axial notches) and an optional neighbouring bore, seen from one view
// direction, with sensor noise along the view direction, salt-and-pepper outliers and ghost points.
// It returns the ground truth. Not a sensor model: the CSS simulator lives in sim/css_*.
// Dense real scans are approximated by several passes of the ray grid (the CSS's scan circles
// pass every spot twice), and a thick-walled pipe (inner and outer wall, no plate) by
// outer_radius.

#include <Eigen/Geometry>
#include <cstdint>

#include "detect/common/point_cloud.hpp"

namespace rangefit::sim {

enum class TopSurface { kPlane, kCurved, kBumpy };
enum class BoreEdge { kSharp, kChamfer, kRounded };

struct SyntheticBoreOptions {
  double radius = 5.0;     // bore radius, mm
  double depth = 0.0;      // blind bore depth along the axis, mm; 0: 6 radii
  double slant_deg = 0.0;  // angle between the bore axis and the top-surface normal, deg
  TopSurface surface = TopSurface::kPlane;
  double curvature_radius = 400.0;  // kCurved: cylindrical curvature radius, mm
  double bump_amplitude = 0.05;     // kBumpy: height amplitude, mm
  double bump_wavelength = 7.0;     // kBumpy: wavelength, mm
  BoreEdge edge = BoreEdge::kSharp;
  double edge_size = 0.8;               // chamfer width (45 deg) or rounding radius, mm
  int notches = 0;                      // axial grooves in the wall, spread over the visible side
  double notch_width_deg = 12.0;        // azimuthal width of one groove, deg
  double notch_depth = 0.6;             // radial depth of a groove, mm
  bool neighbour = false;               // a second, parallel bore of the same radius
  double neighbour_gap = 1.0;           // wall-to-wall distance to the neighbour, mm
  double neighbour_azimuth_deg = 90.0;  // where the neighbour sits around the bore, deg
  double view_tilt_deg = 25.0;          // angle between the view direction and the bore axis, deg
  double extent = 0.0;                  // half-size of the scanned square, mm; 0: 2.6 radii
  double spacing = 0.0;                 // ray spacing, mm; 0: radius / 25 within 0.1..0.4
  double noise_sigma = 0.06;            // Gaussian range noise along the view direction, mm
  double outlier_fraction = 0.05;       // salt-and-pepper outliers along the view direction
  double outlier_amplitude = 10.0;      // outliers move up to +- this, mm
  double ghost_fraction = 0.01;         // points floating in front of the true surface
  bool organised = false;               // fill cloud.grid (rows x cols of rays, passes stacked)
  double extent_v = 0.0;                // half-size across the first scan axis, mm; 0: extent
  int passes = 1;  // ray grids over the square, each turned 7 deg and shifted (double coverage)
  double outer_radius = 0.0;  // > radius: a pipe of this outer radius and length depth, no plate
  double march_step = 0.02;   // ray-marching step inside openings, mm (bisection refines)
  // > radius: a cone of cone_half_angle_deg narrowing with depth from this radius at the
  // entrance down into the bore (a countersink); radius below anything the cone reaches: a
  // pure conical (tapered) hole, mm.
  double cone_radius = 0.0;
  double cone_half_angle_deg = 45.0;
  // > 0: an elliptic bore, radius the semi-axis along major_azimuth_deg (about the axis, from
  // the side the view tilts toward) and radius2 across it, mm.
  double radius2 = 0.0;
  double major_azimuth_deg = 30.0;
  Eigen::Isometry3d T_world_part = Eigen::Isometry3d::Identity();
  std::uint64_t seed = 1;
};

struct SyntheticBoreTruth {
  Eigen::Vector3d entrance;      // axis meets the top surface's mean plane around the bore, mm
  Eigen::Vector3d axis;          // unit, out of the bore toward the sensor side
  double radius = 0.0;           // mm
  double outer_radius = 0.0;     // the pipe's outer wall, mm; 0: a bore in a plate
  Eigen::Vector3d plane_normal;  // unit top-surface normal at the bore
  Eigen::Vector3d view_dir;      // unit, from the surface toward the sensor
  double cone_radius = 0.0;      // a cone's radius at the entrance, mm; 0: no cone
  double half_angle = 0.0;       // the cone's half-angle, rad
  double radius2 = 0.0;          // an ellipse's semi-axis across major_axis, mm; 0: circular
  Eigen::Vector3d major_axis = Eigen::Vector3d::UnitX();  // unit, the direction of radius
};

struct SyntheticBoreScan {
  PointCloud cloud;
  SyntheticBoreTruth truth;
};

// Deterministic for a given options value (seed included). Invalid sizes give an empty cloud.
SyntheticBoreScan make_synthetic_bore(const SyntheticBoreOptions& options);

}  // namespace rangefit::sim
