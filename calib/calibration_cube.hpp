#pragma once
// The hollow calibration cube of thesis 3.2.2 as the calibration sees it: a wire-frame cube of
// twelve square bars (edge : bar = 10 : 1, fig. 3.6a). From any viewpoint outside it a sensor
// sees six planes: three "outer" faces turned towards it and, through the hollow, the three
// "inner" faces of the bars on the far side, which face the same three ways. Intersecting one
// plane of each direction gives the 2 x 2 x 2 = 8 corner points the calibration is built on
// (3.2.3). All lengths mm; the cube frame has its origin at the centre, axes along the edges.

#include <Eigen/Geometry>
#include <array>

namespace rangefit::calib {

struct CalibrationCube {
  double edge_mm = 120.0;  // outer edge length
  double bar_mm = 12.0;    // square bar cross-section
};

// A plane n . x = offset with unit n facing the sensor.
struct CubePlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset_mm = 0.0;
  int axis = 0;       // cube axis the normal is along
  bool outer = true;  // outer face (towards the sensor) or inner face of a far bar
  double distance(const Eigen::Vector3d& p) const { return normal.dot(p) - offset_mm; }
};

// The six visible planes in frame F for a sensor looking from direction `towards_sensor_F` (any
// vector from the cube towards the sensor, frame F), T_F_cube the cube's pose. Index 2 a + o:
// axis a, o = 0 outer, 1 inner.
std::array<CubePlane, 6> visible_planes(const CalibrationCube& cube,
                                        const Eigen::Isometry3d& T_F_cube,
                                        const Eigen::Vector3d& towards_sensor_F);

// Corner c (bits 0..2: inner plane of axis 0..2 instead of outer) of the planes above.
Eigen::Vector3d corner_point(const std::array<CubePlane, 6>& planes, int c);

// Intersection of three planes; NaN when two are parallel.
Eigen::Vector3d intersect_planes(const Eigen::Vector3d& n0, double d0, const Eigen::Vector3d& n1,
                                 double d1, const Eigen::Vector3d& n2, double d2);

}  // namespace rangefit::calib
