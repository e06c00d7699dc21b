#pragma once
// Scenes built in code for the simulator tests (no files needed).

#include <cmath>

#include "hal/css_geometry.hpp"
#include "sim/bore_plate_mesh.hpp"
#include "sim/scene.hpp"

namespace rangefit::sim::testing {

// The work piece frame of a CSS scan (thesis fig. 4.14): the surface z = 0 of this frame is the
// world plane z = R through the sensor's standoff point at omega = 0, facing +z; the sensor
// looks at it tilted by eta = 28.8 deg, as on the FibreScope cell.
inline Eigen::Isometry3d css_facing_pose() {
  const hal::CssGeometry g;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0.0, 0.0, g.pivot_radius_mm);
  return T;
}

// A plane with a box and a sphere standing on it, all under the CSS's scan path.
inline Scene css_analytic_scene() {
  Scene s;
  const Eigen::Isometry3d base = css_facing_pose();
  s.objects.push_back({"floor", PlaneShape{300.0, 300.0}, base});
  Eigen::Isometry3d box = base;
  box.translation() += base.linear() * Eigen::Vector3d(-12.0, 4.0, 4.0);
  s.objects.push_back({"block", BoxShape{Eigen::Vector3d(10.0, 12.0, 8.0)}, box});
  Eigen::Isometry3d ball = base;
  ball.translation() += base.linear() * Eigen::Vector3d(14.0, -3.0, 0.0);
  s.objects.push_back({"ball", SphereShape{5.0}, ball});
  Eigen::Isometry3d post = base;
  post.translation() += base.linear() * Eigen::Vector3d(0.0, 8.0, 5.0);
  s.objects.push_back({"post", CylinderShape{3.0, 10.0}, post});
  return s;
}

// A plate with one bore of the given kind, opening at the CSS's nominal standoff point.
inline Scene css_bore_scene(BoreKind kind, double diameter_mm) {
  BorePlateSpec spec;
  BoreSpec b;
  b.name = "bore";
  b.kind = kind;
  b.diameter_mm = diameter_mm;
  spec.bores.push_back(b);
  BorePlate plate = make_bore_plate(spec);
  Scene s;
  const Eigen::Isometry3d T = css_facing_pose();
  s.objects.push_back({"plate", MeshShape{plate.mesh, "bore_plate"}, T});
  for (BoreTruth t : plate.bores) {
    t.opening_mm = T * t.opening_mm;
    t.axis = T.linear() * t.axis;
    s.bores.push_back(t);
  }
  return s;
}

}  // namespace rangefit::sim::testing
