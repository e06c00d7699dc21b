#pragma once
// Where the rays that measured a scan came from, as far as visibility goes. A laser-stripe
// ranger measures a point only when its laser fan reaches it and its camera sees the lit spot,
// so a point needs two unobstructed lines of sight (with a second camera on the other side of
// the laser plane, the laser's and either camera's); a range camera or a time-of-flight ranger at
// one place needs one. Detection uses this to tell the surface a part could have shown this
// scan (and was not measured: evidence against it) from the surface this sensor could never
// have seen (shadows: no evidence either way). Beyond the thesis, whose coverage-free vote
// assumed one fixed viewpoint.
//
// All vectors are in the frame of the scan's points (mm, rad).

#include <Eigen/Core>
#include <array>
#include <optional>

namespace rangefit {

struct SensorView {
  enum class Kind {
    kUnknown,      // nothing known: detection falls back to the scan's own evidence
    kPoint,        // one eye at `origin` (pinhole camera, a single ranger position)
    kLinearSweep,  // a stripe ranger moved along `direction` (stripe cell: the table moves)
    kRotarySweep,  // a stripe ranger turned about the line (`pivot`, `direction`) (pan-tilt head)
  };
  Kind kind = Kind::kUnknown;
  // kPoint: the eye. Sweeps: the laser fan's apex at sweep position 0.
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  // Sweeps: the laser plane's normal at sweep position 0, and the camera's projection centre
  // relative to the apex at position 0 (zero: the ranger has no separate camera, one eye).
  Eigen::Vector3d plane_normal = Eigen::Vector3d::UnitY();
  Eigen::Vector3d camera_offset = Eigen::Vector3d::Zero();
  // Sweeps: a second camera of the same laser plane, relative to the apex at position 0, whose
  // profiles were merged with the first's (zero: none). A point lit by the laser is measured
  // when either camera sees it, so a surface one camera has in its shadow the other may show.
  Eigen::Vector3d second_camera_offset = Eigen::Vector3d::Zero();
  // kLinearSweep: unit direction the ranger moves relative to the points per mm of sweep.
  // kRotarySweep: unit axis of the turn (right hand), through `pivot`; sweep in rad.
  Eigen::Vector3d direction = Eigen::Vector3d::UnitY();
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();
  double sweep_min = 0.0;  // the sweep positions the scan covered (mm or rad)
  double sweep_max = 0.0;
};

// The eyes that see p when it is measured: 0 when the view is unknown or no sweep position
// inside [sweep_min, sweep_max] puts p in the laser plane, else the laser apex (or the only
// eye) first, then the cameras. The first eye must see p, and of the others (the cameras) any
// one.
struct Eyes {
  int count = 0;
  std::array<Eigen::Vector3d, 3> at{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                    Eigen::Vector3d::Zero()};
};
Eyes sensor_eyes(const SensorView& view, const Eigen::Vector3d& p);

// Sweeps: the sweep position (mm or rad) whose laser plane holds p, within [sweep_min,
// sweep_max]; nullopt otherwise and for the other kinds.
std::optional<double> sweep_position(const SensorView& view, const Eigen::Vector3d& p);

// Sweeps: the laser fan's apex, its plane's normal and the cameras' offsets at sweep position s.
struct SweepPose {
  Eigen::Vector3d apex, plane_normal, camera_offset, second_camera_offset;
};
SweepPose sweep_pose(const SensorView& view, double s);
// The eyes of a sweep at `pose` (as sensor_eyes orders them).
Eyes sweep_eyes(const SweepPose& pose);

// Two sweeps of one laser fan seen by two cameras (a stripe cell's cameras on either side of
// its laser plane, each sweeping in turn over the same range) as one view: `first` with
// `second`'s camera as its second camera. Nullopt unless both are sweeps of the same kind with
// one camera each, their planes, directions (and pivots) agree, `second`'s apex lies in `first`'s
// laser plane within tolerance_mm, their sweep ranges agree (within tolerance_mm, or
// tolerance_rad for a turn) and the cameras stand apart by more than tolerance_mm.
std::optional<SensorView> with_second_camera(const SensorView& first, const SensorView& second,
                                             double tolerance_mm = 0.5,
                                             double tolerance_rad = 1e-4);

// False for non-finite fields, a non-unit direction or normal, an empty sweep, or a linear sweep
// that runs inside its own laser plane (it would never sweep the plane across anything).
bool valid(const SensorView& view);

}  // namespace rangefit
