#pragma once
// Surface evidence for a posed part: of the surface this scan could have measured, how much it
// did measure, and how much of it lies where the sensor saw past it. Beyond the thesis: M, I and
// S (eq. 5.2-5.4) only look at the points near a hypothesis, so a part posed against a fragment
// of another object (a flat box on a cylinder's cap, a shaft along an edge) fits well and is
// empty inside, yet claims surface the sensor would have seen. Used to confirm a detection.
//
// "Could have measured" is decided per surface sample by the sensor's own visibility: the sample
// faces every eye the sensor needed for it (a stripe ranger needs its laser apex and its camera,
// detect/sensor_view.hpp) and no measured surface lies between it and them. Surface in a laser
// or camera shadow, hidden behind another object or outside the sweep is then no evidence
// either way, whatever the triangulation angle, camera side or stand-off.

#include <Eigen/Geometry>
#include <optional>
#include <span>

#include "detect/common/kdtree.hpp"
#include "detect/common/laser_shadow.hpp"
#include "detect/common/occupancy_grid.hpp"
#include "detect/common/pca.hpp"
#include "detect/common/sensor_view.hpp"
#include "detect/object/superquadric.hpp"

namespace rangefit {

struct CoverageOptions {
  int samples = 200;                   // surface samples (about half of them visible)
  double tolerance_mm = 3.0;           // a sample is covered by a point this close
  double tolerance_of_min_size = 0.1;  // ... or this share of the smallest size, if larger
  // How the scan was taken. Unknown: the part is judged as seen from far away along the side the
  // points near it lie on, and, with a removed plane, from above that plane.
  SensorView sensor;
  // Samples this close to the removed plane are not checked (their points went with it). Its
  // normal points to the side the scan's objects are on.
  std::optional<pca::Plane> removed_plane;
  double plane_margin_mm = 5.0;
  // The side wall by each flat end of a part with flat caps (eps1 <= 0.5, no taper): end_rings
  // rings of end_ring_samples samples spread over end_strip of its half-length from the cap, and
  // as many farther in; then all of those against end_rings rings over twice end_strip farther in
  // (object_coverage.cpp open_ends). A part fitted to a shorter look-alike lying along the sweep
  // (its caps face along the sweep and show no points) reaches past the look-alike's end, where the
  // sensor saw no surface; the few of the 200 samples there are lost among the rest.
  double end_strip = 0.2;
  int end_rings = 4;
  int end_ring_samples = 16;
  int min_end_samples = 8;  // an end (or a rim's sector) with fewer measurable samples is not
                            // judged
  // The rims of the flat caps (and of a box's every face), by sector: rim_rings rings over
  // rim_strip of the cap's radius from its edge, and as many farther in, rim_sector_samples
  // samples per ring and sector (object_coverage.cpp open_rim).
  double rim_strip = 0.2;
  int rim_rings = 4;
  int rim_sector_samples = 6;
  // The whole scan (plane included) as occupied cells: lines of sight blocked by it are
  // occluded, and a line of sight that runs on past a sample to a measured cell saw past it.
  // Without it nothing counts as occluded or seen past.
  const OccupancyGrid* occupancy = nullptr;
  // The laser's shadow of the scan (with a stripe ranger's sensor): a camera's line of sight
  // through it is not known to be clear. Only with `occupancy`.
  const LaserShadow* laser_shadow = nullptr;
  // Nor is one through space the laser never lit (LaserShadow::unlit) within this share of the
  // part's largest size from the sample: a wall beside a sweep that stopped short of it hides
  // the part's end from the camera and leaves no point of its own. Farther out the line is taken
  // as clear: counted unknown all the way to the scan's edge, it hid the bare strips that tell
  // a look-alike near that edge from the part (pan-tilt tuning seeds 364 and 476 took a box 8 %
  // narrower or 19 % shorter for the box).
  double unlit_reach_of_max_size = 1.0;
};

struct SurfaceCoverage {
  int facing = 0;               // samples facing every eye (the rest are in the part's own shadow
                                // or grazed), and the grazed ones below
  int measurable = 0;           // of them, the ones no measured surface hides: the sensor could
                                // have measured them
  int grazed = 0;               // of them, seen too obliquely to judge (~75-87 deg) but with a scan
                                // point on them: evidence the part is there, in no share below
  double covered = 0.0;         // share of them with a scan point near them
  double seen_through = 0.0;    // share of them the sensor saw past: free space
  double open_end = 0.0;        // of the measurable samples by a flat end whose side wall the
                                // scan shows farther in, the largest share (of the two ends and
                                // both scales) with no scan points near them
  // Per end (the one at -z, the one at +z): the share over end_strip against as far again
  // farther in; and over twice end_strip against as far again (a part reaching past the
  // surface's end by more than end_strip).
  double open_end_at[2] = {0.0, 0.0};
  double open_end_far_at[2] = {0.0, 0.0};
  // Per flat end: not judged, and its side wall by the end hidden by measured surface in front
  // of it (a wall, an overhang), so where the scan stops short of it says nothing of the part's
  // length. False for a part without flat ends.
  bool end_hidden[2] = {false, false};
  double open_rim = 0.0;        // of the measurable samples by a flat cap's edge, where the scan
                                // shows the cap farther in, the largest share (per cap and
                                // sector) with no scan points near them
  double open_rim_far = 0.0;    // the same over twice rim_strip against as far again farther in
  double below_plane_mm = 0.0;  // how far the part (as modelled) reaches through the removed plane
  double lowest_mm = 0.0;       // height of its lowest point above the removed plane, its flat
                                // faces' rounded edges taken as sharp (refined on the surface's
                                // parametrisation, to ~0.01 mm)
  Eigen::Vector3d deepest_part = Eigen::Vector3d::Zero();  // the model's lowest point, part
                                                           // frame (below_plane_mm is its depth)
  double min_size_mm = 0.0;     // the part's smallest size parameter
  double max_size_mm = 0.0;     // and its largest
};

// Which of the coverage's measures to take; the others are left at their defaults. `surface`:
// the samples over the whole surface (facing, measurable, grazed, covered, seen_through) and the
// part's place against the removed plane (below_plane_mm, lowest_mm, deepest_part); `ends`: the
// rings by its flat ends (open_end*, end_hidden); `rims`: its flat caps' rims (open_rim*). A check
// that needs only some of them pays only for those: a box's rims are ~6 times as many samples
// as its surface.
struct CoverageMeasures {
  bool surface = true, ends = true, rims = true;
};
inline constexpr CoverageMeasures kSurfaceOnly{.surface = true, .ends = false, .rims = false};
inline constexpr CoverageMeasures kEndsOnly{.surface = false, .ends = true, .rims = false};
inline constexpr CoverageMeasures kEndsAndRims{.surface = false, .ends = true, .rims = true};

// Samples are spread over the surface evenly in the part's normalised coordinates (exactly even
// for a sphere). Shares are 0 when no sample was measurable.
SurfaceCoverage surface_coverage(const Superquadric& sq, const Eigen::Isometry3d& T_world_part,
                                 std::span<const Eigen::Vector3d> points, const KdTree& tree,
                                 const CoverageOptions& options = {},
                                 CoverageMeasures measures = {});

// `c` with the ends' and rims' measures of `edges` (a coverage of the same part and pose taken
// with `surface` off).
void take_edges(SurfaceCoverage& c, const SurfaceCoverage& edges);

}  // namespace rangefit
