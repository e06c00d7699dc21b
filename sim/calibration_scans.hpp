#pragma once
// Simulated scans of the calibration bodies (thesis 3.2): the hollow cube of twelve square bars
// ("a wire-frame model of a cube" built from aluminium profiles, fig. 3.6a) on the stripe cell's
// table or in front of the pan-tilt head, and a precision sphere scanned by the CSS on the robot's
// last joint. They produce the raw samples a real cell records (ranger profiles with their axis
// position or pan/tilt angles; CSS ranges with the joint angle), from a true geometry the
// calibration under test does not see. All lengths mm, angles rad.

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "hal/css_geometry.hpp"
#include "hal/pan_tilt_geometry.hpp"
#include "hal/samples.hpp"
#include "hal/stripe_geometry.hpp"
#include "sim/scene.hpp"

namespace rangefit::sim {

// The cube [-edge/2, edge/2]^3 in its own frame, its twelve edges square bars `bar_mm` thick
// lying inside the cube (thesis: edge to bar 10:1). With `table`, a table top at scene z = 0.
Scene calibration_cube_scene(double edge_mm, double bar_mm, const Eigen::Isometry3d& T_scene_cube,
                             bool table);

struct RangerNoise {
  double sigma_mm = 0.0;  // Gaussian, along the fan ray (a shifted peak on the chip)
  bool quantise = false;  // round depths to the chip's 1536 rows (sim/ranger_simulator.hpp)
  std::uint64_t seed = 1;
};

// One profile per axis position: the cell's ranger (true `cell` geometry) over the scene (scene
// frame = the cell's table frame at axis position 0).
std::vector<hal::RangerProfile> simulate_stripe_sweep(const Scene& scene,
                                                      const hal::StripeCellGeometry& cell,
                                                      const std::vector<double>& axis_mm,
                                                      const RangerNoise& noise);

// One profile per (pan, tilt) pair (reported angles), the head's world frame = the scene frame.
std::vector<hal::RangerProfile> simulate_pan_tilt_sweep(
    const Scene& scene, const hal::PanTiltGeometry& head,
    const std::vector<hal::PanTiltSample>& angles, const RangerNoise& noise);

// A CSS scan of a sphere: the robot holds its last joint's frame at T_base_joint, the joint turns
// through the reported angles `omega` (rad, one revolution each); samples without a return are
// left out. The true sensor pose on the joint is T_joint_css(omega - omega_zero).
struct CssRangeSample {
  double omega_rad = 0.0;  // reported joint angle
  double beam_rad = 0.0;   // beam angle (hal::CssGeometry::beam_angle)
  double range_mm = 0.0;   // along the beam from p_LD
};
std::vector<CssRangeSample> simulate_css_sphere_scan(
    const hal::CssGeometry& sensor, const Eigen::Isometry3d& T_joint_css, double omega_zero_rad,
    const Eigen::Isometry3d& T_base_joint, const std::vector<double>& omega,
    const Eigen::Vector3d& centre_base_mm, double radius_mm, double sigma_mm, std::uint64_t seed);

}  // namespace rangefit::sim
