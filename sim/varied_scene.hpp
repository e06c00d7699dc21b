#pragma once
// Seeded "varied" laser-stripe scenes for testing and benchmarking object detection (thesis ch.
// 5) on what a single pinhole render does not vary: the triangulation angle and side of the
// camera (laser and camera shadows), the ranger's height and tilt, stripe cell or pan-tilt
// head, profile spacing, range noise and outliers along the laser ray, occlusion of the target
// by a wall or an overhang, a target cut by the end of the sweep, and clutter: look-alikes of
// the model 4-20 % larger or smaller, cans, boxes, balls, other superquadrics, standing and
// lying, touching or close to each other. The thesis scenes (fig. 5.18, 5.28, the mallet among
// look-alikes) come as instances under any scan setup. A pan-tilt head's cameras stay at least
// 50 mm above the table over the whole sweep (setups that would take one under it are drawn
// again).
//
// Points are in the table frame (z up, table surface z = 0, mm), the frame of `view`.
//
// Seeds: 1..1000 (kTuningSeedBase + i) are the tuning set; seeds from kHeldOutSeedBase
// (1000001) on are held out: look at their results only to report them, never to tune.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "detect/object/object_model.hpp"
#include "detect/common/point_cloud.hpp"
#include "detect/common/sensor_view.hpp"
#include "sim/stripe_sweep.hpp"
#include "sim/superquadric_raycast.hpp"

namespace rangefit::sim {

inline constexpr std::uint64_t kTuningSeedBase = 1;  // tuning seeds 1..1000
inline constexpr std::uint64_t kTuningSeedCount = 1000;
inline constexpr std::uint64_t kHeldOutSeedBase = 1000001;  // held out: 1000001, 1000002, ...

enum class VariedTarget { kSphere, kCylinder, kBox, kCone, kMallet, kThreeSpheres, kNone };
const char* to_string(VariedTarget target);
std::optional<VariedTarget> varied_target_from(const std::string& name);  // to_string's inverse

// Every factor is drawn uniformly from [min, max]; min == max fixes it.
struct VariedSceneOptions {
  VariedTarget target = VariedTarget::kSphere;
  bool pan_tilt = false;  // false: stripe cell (linear sweep); true: pan-tilt head (rotary)
  double triangulation_min_deg = 15.0, triangulation_max_deg = 50.0;  // camera ray vs laser ray
  int camera_side = 0;  // 0: drawn; +1 / -1: that side of the laser plane
  // Chance of a second camera on the other side of the laser plane (ScanSetup::two_cameras).
  double two_camera_probability = 0.0;
  double laser_height_min_mm = 300.0, laser_height_max_mm = 900.0;
  double laser_tilt_max_deg = 10.0;  // stripe cell: laser plane off vertical, drawn in +-max
  double pan_tilt_view_min_deg = 15.0, pan_tilt_view_max_deg = 45.0;  // head: view off vertical
  double step_min_mm = 0.3, step_max_mm = 2.0;                        // profile spacing
  int points_per_profile = 0;  // fan rays; 0: as many as max_points allows (at most 2048)
  double max_points = 150000;  // profiles x rays at most (the rays give way)
  double noise_min_mm = 0.0, noise_max_mm = 1.0;  // sigma along the laser ray
  double outlier_share_max = 0.002;
  // Share of the target's measurable surface an occluder hides (below 0.02: no occluder).
  double occlusion_min = 0.1, occlusion_max = 0.6;
  double partly_outside_probability = 0.1;  // the sweep starts or ends inside the target
  bool clutter = true;
  int clutter_min = 2, clutter_max = 6;        // objects besides look-alikes
  int lookalikes_min = 1, lookalikes_max = 2;  // of the model (three spheres: always two more)
  double lookalike_min = 0.04, lookalike_max = 0.20;  // look-alike size ratio off 1
  double near_probability = 0.5;  // a clutter object is put touching or close to another
  // Objects stand inside this rectangle centred at 0 (x along the laser line, y along the
  // sweep); scenes with a mallet use it x mallet_workspace_scale.
  double workspace_x_mm = 360.0, workspace_y_mm = 400.0;
  double mallet_workspace_scale = 1.25;
  int threads = 0;  // ray casting; 0: all cores (the scene does not depend on it)
};

struct VariedScene {
  PointCloud cloud;                   // table frame; organised: rows are profiles, columns fan rays
  std::vector<std::int32_t> label;    // per point: index into parts, -1 table, -2 outlier
  std::vector<std::int32_t> profile;  // per point: its profile (sweep.position(profile))
  std::vector<ScenePart> parts;       // ground truth: target, occluder, look-alikes, clutter
  std::vector<int> target_parts;      // parts[target_parts[i]] is model.parts[i]; empty: kNone
  ObjectModel model;                  // what to search for
  SensorView view;                    // exactly how the scan was taken (= sweep.view())
  StripeSweep sweep;                  // every profile's apex and camera (sweep.pose)
  struct Factors {
    ScanSetup scan;                  // as drawn (fan and rays follow: sweep.fan_rad, .rays)
    double occlusion_requested = 0;  // drawn share of the target's measurable surface to hide
    double occlusion = 0;            // achieved: share hidden by all other objects
    double outside = 0;              // share of the target's seeable surface outside the scan
    // The largest share of one target part's seeable surface the scan lacks, hidden or outside:
    // a mallet whose shaft lies outside the sweep has lost 1.0 of it, whatever its head shows.
    double part_lost = 0;
    std::string occluder = "none";   // "none", "wall" or "overhang"
    double lookalike_ratio = 0;      // look-alikes are (1 +- ratio) x the model's sizes
    int lookalikes = 0;
    int clutter = 0;  // other objects
  } factors;
};

VariedScene make_varied_scene(const VariedSceneOptions& options, std::uint64_t seed);

// Scans given parts on the sweep (noise and outliers of factors.scan, drawn from the seed) and
// measures the target's occlusion and outside share into the factors. parts[target_parts[i]]
// is model.parts[i].
VariedScene scan_varied_scene(std::vector<ScenePart> parts, std::vector<int> target_parts,
                              ObjectModel model, const StripeSweep& sweep,
                              VariedScene::Factors factors, std::uint64_t seed, int threads = 0);

// The thesis scenes with their own poses (test/detect/object_scenes.hpp) under a given scan:
// kCylinder, kBox, kSphere, kCone: fig. 5.18 (table 5.3 poses), that object the target;
// kThreeSpheres: fig. 5.28 (radii 48, 50, 52; the 50 is the target); kMallet: the mallet among
// look-alikes and two occluding boxes; kNone: that scene without the mallet (model: the mallet).
// The seed draws the noise and outliers of `scan`.
VariedScene thesis_scene(VariedTarget which, const ScanSetup& scan, std::uint64_t seed,
                         int threads = 0);

}  // namespace rangefit::sim
