#include "sim/varied_scene.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "detect/common/angles.hpp"
#include "sim/occluder.hpp"
#include "sim/scene_objects.hpp"
#include "sim/stripe_scan.hpp"
#include "sim/visible_surface.hpp"

namespace rangefit::sim {
namespace {

constexpr double kCoverHeightMm = 120.0;  // the fan reaches every point of the workspace up to this
constexpr double kMinCameraHeightMm = 50.0;  // cameras stay this far above the table top
constexpr int kMaxSetupRedraws = 100;
constexpr double kObjectGapMm = 0.5;      // bounding boxes at least this far apart
constexpr double kMaxAddedOcclusion = 0.04;  // clutter may hide this much more than drawn
constexpr int kPlacementTries = 60;

std::uint64_t mix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

class Draw {
 public:
  explicit Draw(std::uint64_t seed) : rng_(mix(seed)) {}
  double uniform(double lo, double hi) {
    return hi > lo ? std::uniform_real_distribution<double>(lo, hi)(rng_) : lo;
  }
  int integer(int lo, int hi) {
    return hi > lo ? std::uniform_int_distribution<int>(lo, hi)(rng_) : lo;
  }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }
  std::mt19937_64& rng() { return rng_; }

 private:
  std::mt19937_64 rng_;
};

ObjectModel single(const std::string& name, const Superquadric& sq) {
  return ObjectModel{name, {ModelPart{name, sq}}, {}};
}

ObjectModel model_of(VariedTarget t) {
  switch (t) {
    case VariedTarget::kCylinder:
      return single("cylinder", cylinder_model());
    case VariedTarget::kBox:
      return single("box", box_model());
    case VariedTarget::kCone:
      return single("cone", cone_model());
    case VariedTarget::kMallet:
      return mallet_model();
    default:
      return single("sphere", sphere_model());
  }
}

bool inside(const TableObject& o, const Eigen::AlignedBox2d& ws) {
  const Eigen::AlignedBox3d b = object_bounds(o);
  return ws.contains(Eigen::Vector2d(b.min().x(), b.min().y())) &&
         ws.contains(Eigen::Vector2d(b.max().x(), b.max().y()));
}

bool overlaps_any(const TableObject& o, const std::vector<TableObject>& placed) {
  for (const TableObject& p : placed) {
    if (objects_overlap(o, p, kObjectGapMm)) return true;
  }
  return false;
}

// Puts `o` (turned to a new yaw after each failed try) anywhere in the workspace clear of
// `placed`, or with near_probability (near) touching one of the first `anchors` of them; false
// when no free spot was found. `accept` may veto a spot.
bool put(TableObject& o, std::size_t anchors, const std::vector<TableObject>& placed,
         const Eigen::AlignedBox2d& ws, double near_probability, Draw& d,
         const std::function<bool(const TableObject&)>& accept = nullptr) {
  anchors = std::min(anchors, placed.size());
  for (int i = 0; i < kPlacementTries; ++i) {
    place(o, 0.0, 0.0, 0.0);
    const Eigen::Vector3d half = 0.5 * object_bounds(o).sizes();
    // One draw per statement: a call's arguments are evaluated in an unspecified order (GCC
    // right to left, clang left to right), and a seed must make the same scene with either.
    const double y = d.uniform(ws.min().y() + half.y(), ws.max().y() - half.y());
    const double x = d.uniform(ws.min().x() + half.x(), ws.max().x() - half.x());
    Eigen::Vector2d xy(x, y);
    if (anchors > 0 && d.chance(near_probability)) {
      const TableObject& anchor =
          placed[static_cast<std::size_t>(d.integer(0, static_cast<int>(anchors) - 1))];
      const double phi = d.uniform(0.0, 2.0 * std::numbers::pi);
      const Eigen::Vector3d u(std::cos(phi), std::sin(phi), 0.0);
      const Eigen::Vector3d a = object_bounds(anchor).center();
      const double dist = reach(anchor, u) - u.dot(a) + reach(o, -u) + d.uniform(0.0, 15.0);
      xy = Eigen::Vector2d(a.x(), a.y()) + dist * Eigen::Vector2d(u.x(), u.y());
    }
    place(o, xy.x(), xy.y(), 0.0);
    if (inside(o, ws) && !overlaps_any(o, placed) && (!accept || accept(o))) return true;
    place(o, 0.0, 0.0, d.uniform(0.0, 2.0 * std::numbers::pi));
  }
  return false;
}

ScanSetup draw_setup(const VariedSceneOptions& o, Draw& d) {
  ScanSetup s;
  s.pan_tilt = o.pan_tilt;
  s.triangulation_deg = d.uniform(o.triangulation_min_deg, o.triangulation_max_deg);
  s.camera_side = o.camera_side != 0 ? (o.camera_side > 0 ? 1 : -1) : (d.chance(0.5) ? 1 : -1);
  s.laser_height_mm = d.uniform(o.laser_height_min_mm, o.laser_height_max_mm);
  s.laser_tilt_deg = o.pan_tilt ? d.uniform(o.pan_tilt_view_min_deg, o.pan_tilt_view_max_deg)
                                : d.uniform(-o.laser_tilt_max_deg, o.laser_tilt_max_deg);
  s.step_mm = d.uniform(o.step_min_mm, o.step_max_mm);
  s.points_per_profile = o.points_per_profile;
  s.max_points = o.max_points;
  s.noise_mm = d.uniform(o.noise_min_mm, o.noise_max_mm);
  s.outlier_share = d.uniform(0.0, o.outlier_share_max);
  // Drawn only when asked for, so that one-camera scenes stay as they were drawn.
  if (o.two_camera_probability > 0.0) s.two_cameras = d.chance(o.two_camera_probability);
  return s;
}

// The lowest height above the table a camera of the sweep reaches (at its ends, and in between
// for a turning head, whose cameras move on circles).
double lowest_camera(const StripeSweep& w) {
  constexpr int kChecks = 16;
  double lowest = INFINITY;
  for (int i = 0; i <= kChecks; ++i) {
    const double s = w.position(0) + (w.position(w.profiles - 1) - w.position(0)) * i / kChecks;
    const ProfilePose pose = w.pose(s);
    lowest = std::min(lowest, pose.camera.z());
    if (pose.second_camera) lowest = std::min(lowest, pose.second_camera->z());
  }
  return lowest;
}

std::vector<int> indices(std::size_t n) {
  std::vector<int> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<int>(i);
  return v;
}

// The sweep starts or ends across the target, leaving 10-60 % of what the sensor would see of
// it (`seeable`) outside.
void cut_sweep_through(StripeSweep& w, const ScanSetup& scan,
                       const std::vector<SurfaceSample>& seeable, Draw& d) {
  std::vector<double> s;
  for (const SurfaceSample& p : seeable) s.push_back(w.position_of(p.point));
  if (s.empty()) return;
  std::sort(s.begin(), s.end());
  const bool cut_start = d.chance(0.5);
  const double q = d.uniform(0.1, 0.6);
  const double at = (cut_start ? q : 1.0 - q) * static_cast<double>(s.size() - 1);
  const double cut = s[static_cast<std::size_t>(at)];
  const double start = cut_start ? cut : w.sweep_start;
  const double stop = cut_start ? w.position(w.profiles - 1) : cut;
  w.sweep_start = start;
  w.profiles = std::max(2, static_cast<int>(std::floor((stop - start) / w.sweep_step)) + 1);
  w.rays = rays_for(scan, w.profiles);
}

// The target's measurable surface (`samples`) and what the objects placed so far hide of it.
struct TargetView {
  std::vector<SurfaceSample> samples;
  std::vector<bool> hidden;
  double share() const { return weighted_share(samples, hidden); }
  // The hidden share once `o` is added too.
  double share_with(const TableObject& o) const {
    std::vector<bool> h = hidden_by(samples, PartCaster(o.parts));
    for (std::size_t i = 0; i < h.size(); ++i) h[i] = h[i] || hidden[i];
    return weighted_share(samples, h);
  }
  void add(const TableObject& o) {
    const std::vector<bool> h = hidden_by(samples, PartCaster(o.parts));
    for (std::size_t i = 0; i < h.size(); ++i) hidden[i] = hidden[i] || h[i];
  }
};

// Factors::part_lost: per target part, the share of what the sensor would see of it (the target
// alone hiding itself, the sweep uncut) that the scan does not measure.
double largest_part_loss(const std::vector<ScenePart>& target, const std::vector<ScenePart>& others,
                         const StripeSweep& sweep) {
  const PartCaster alone(target), rest(others);
  double lost = 0.0;
  for (std::size_t i = 0; i < target.size(); ++i) {
    const std::vector<int> part = {static_cast<int>(i)};
    const double seeable = total_weight(visible_samples(alone, part, sweep, false));
    if (seeable <= 0.0) continue;
    const std::vector<SurfaceSample> in_scan = visible_samples(alone, part, sweep, true);
    const std::vector<bool> hidden = hidden_by(in_scan, rest);
    const double measured = total_weight(in_scan) * (1.0 - weighted_share(in_scan, hidden));
    lost = std::max(lost, std::clamp(1.0 - measured / seeable, 0.0, 1.0));
  }
  return lost;
}

VariedScene scan(std::vector<ScenePart> parts, std::vector<int> target_parts, ObjectModel model,
                 const StripeSweep& sweep, VariedScene::Factors factors, std::uint64_t seed,
                 int threads) {
  VariedScene s;
  const ScanSetup& setup = factors.scan;
  StripeScan raw = scan_stripe(PartCaster(parts), sweep,
                               {setup.noise_mm, setup.outlier_share, mix(seed ^ 0x5ca9)}, threads);
  s.cloud = std::move(raw.cloud);
  s.label = std::move(raw.label);
  s.profile = std::move(raw.profile);
  s.parts = std::move(parts);
  s.target_parts = std::move(target_parts);
  s.model = std::move(model);
  s.view = sweep.view();
  s.sweep = sweep;
  s.factors = std::move(factors);
  return s;
}

}  // namespace

VariedScene scan_varied_scene(std::vector<ScenePart> parts, std::vector<int> target_parts,
                              ObjectModel model, const StripeSweep& sweep,
                              VariedScene::Factors factors, std::uint64_t seed, int threads) {
  if (!target_parts.empty()) {
    std::vector<ScenePart> target, others;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      const bool in = std::find(target_parts.begin(), target_parts.end(), static_cast<int>(i)) !=
                      target_parts.end();
      (in ? target : others).push_back(parts[i]);
    }
    const PartCaster alone(target);
    const auto samples = visible_samples(alone, indices(target.size()), sweep, true);
    const double seeable =
        total_weight(visible_samples(alone, indices(target.size()), sweep, false));
    factors.occlusion = weighted_share(samples, hidden_by(samples, PartCaster(others)));
    factors.outside = seeable > 0.0 ? std::max(0.0, 1.0 - total_weight(samples) / seeable) : 0.0;
    factors.part_lost = largest_part_loss(target, others, sweep);
  }
  return scan(std::move(parts), std::move(target_parts), std::move(model), sweep,
              std::move(factors), seed, threads);
}

const char* to_string(VariedTarget t) {
  switch (t) {
    case VariedTarget::kSphere:
      return "sphere";
    case VariedTarget::kCylinder:
      return "cylinder";
    case VariedTarget::kBox:
      return "box";
    case VariedTarget::kCone:
      return "cone";
    case VariedTarget::kMallet:
      return "mallet";
    case VariedTarget::kThreeSpheres:
      return "three_spheres";
    case VariedTarget::kNone:
      return "none";
  }
  return "?";
}

std::optional<VariedTarget> varied_target_from(const std::string& name) {
  for (VariedTarget t :
       {VariedTarget::kSphere, VariedTarget::kCylinder, VariedTarget::kBox, VariedTarget::kCone,
        VariedTarget::kMallet, VariedTarget::kThreeSpheres, VariedTarget::kNone}) {
    if (name == to_string(t)) return t;
  }
  return std::nullopt;
}

VariedScene make_varied_scene(const VariedSceneOptions& o, std::uint64_t seed) {
  Draw d(seed);
  VariedScene::Factors f;
  f.scan = draw_setup(o, d);
  // The model; kNone searches for one of the others, which is absent.
  VariedTarget kind = o.target;
  if (kind == VariedTarget::kNone) kind = static_cast<VariedTarget>(d.integer(0, 5));
  const ObjectModel model = model_of(kind);
  f.lookalike_ratio = d.uniform(o.lookalike_min, o.lookalike_max);
  const double ws_scale = kind == VariedTarget::kMallet ? o.mallet_workspace_scale : 1.0;
  const Eigen::Vector2d half = 0.5 * ws_scale * Eigen::Vector2d(o.workspace_x_mm, o.workspace_y_mm);
  const Eigen::AlignedBox2d ws(-half, half);
  const Eigen::AlignedBox3d cover(Eigen::Vector3d(-half.x() - 5, -half.y() - 5, 0.0),
                                  Eigen::Vector3d(half.x() + 5, half.y() + 5, kCoverHeightMm));
  StripeSweep sweep = make_sweep(f.scan, cover);
  // A head's camera turns with it; one that would pass under the table top (a steep view, a wide
  // baseline on the lower side) is no setup anyone builds, and it would see the parts through
  // the table. Drawn again until every camera stays above it over the whole sweep.
  for (int redraw = 0; redraw < kMaxSetupRedraws && lowest_camera(sweep) < kMinCameraHeightMm;
       ++redraw) {
    f.scan = draw_setup(o, d);
    sweep = make_sweep(f.scan, cover);
  }

  std::vector<TableObject> objects;  // target, occluder, look-alikes, clutter
  TargetView target;                 // what the sensor measures of the target alone
  double seeable = 0.0;              // ... and would, were the sweep not cut
  if (o.target != VariedTarget::kNone) {
    TableObject t = kind == VariedTarget::kMallet
                        ? resting_mallet("mallet", d.rng())
                        : resting_part(model.name, model.parts[0].shape,
                                       rest_of(model.parts[0].shape), d.rng());
    put(t, 0, {}, ws, 0.0, d);
    const PartCaster alone(t.parts);
    const std::vector<SurfaceSample> all =
        visible_samples(alone, indices(t.parts.size()), sweep, false);
    seeable = total_weight(all);
    if (d.chance(o.partly_outside_probability)) cut_sweep_through(sweep, f.scan, all, d);
    target.samples = visible_samples(alone, indices(t.parts.size()), sweep, true);
    target.hidden.assign(target.samples.size(), false);
    f.occlusion_requested = d.uniform(o.occlusion_min, o.occlusion_max);
    objects.push_back(std::move(t));
  }
  // The occluder hides the drawn share; every object after it may hide only a little more.
  if (!target.samples.empty() && f.occlusion_requested >= 0.02) {
    Occluder occ = make_occluder(objects.front(), target.samples, target.hidden, sweep,
                                 f.occlusion_requested, d.rng());
    if (!occ.object.parts.empty() && !overlaps_any(occ.object, objects)) {
      f.occluder = occ.kind;
      target.add(occ.object);
      objects.push_back(std::move(occ.object));
    }
  }
  const double budget = f.occlusion_requested + kMaxAddedOcclusion;
  const auto add = [&](TableObject c, std::size_t anchors, double near_probability) {
    const auto spares_target = [&](const TableObject& x) {
      return target.samples.empty() ||
             target.share_with(x) <= std::max(budget, target.share() + 0.005);
    };
    if (!put(c, anchors, objects, ws, near_probability, d, spares_target)) return 0;
    if (!target.samples.empty()) target.add(c);
    objects.push_back(std::move(c));
    return 1;
  };
  if (kind == VariedTarget::kThreeSpheres && !objects.empty()) {
    // Fig. 5.28: a smaller and a larger sphere, mostly close to the target.
    for (double size : {1.0 - f.lookalike_ratio, 1.0 + f.lookalike_ratio}) {
      const double r = 50.0 * size;
      f.lookalikes += add(
          resting_part("lookalike/sphere", {r, r, r, 1, 1, 0, 0}, Rest::kBase, d.rng()), 1, 0.8);
    }
  }
  if (o.clutter) {
    const int n_look = d.integer(o.lookalikes_min, o.lookalikes_max);
    for (int i = 0; i < n_look; ++i) {
      f.lookalikes +=
          add(lookalike(model, f.lookalike_ratio, d.rng()), objects.size(), o.near_probability);
    }
    const int n_clutter = d.integer(o.clutter_min, o.clutter_max);
    for (int i = 0; i < n_clutter; ++i) {
      f.clutter +=
          add(clutter_object(model, o.lookalike_min, d.rng()), objects.size(), o.near_probability);
    }
  }

  const std::size_t n_target = o.target != VariedTarget::kNone ? objects.front().parts.size() : 0;
  if (n_target > 0) {
    f.occlusion = target.share();
    const double measured = total_weight(target.samples);
    f.outside = seeable > 0.0 ? std::max(0.0, 1.0 - measured / seeable) : 0.0;
    std::vector<ScenePart> others;
    for (std::size_t i = 1; i < objects.size(); ++i) {
      others.insert(others.end(), objects[i].parts.begin(), objects[i].parts.end());
    }
    f.part_lost = largest_part_loss(objects.front().parts, others, sweep);
  }
  std::vector<ScenePart> parts;
  for (const TableObject& obj : objects) {
    parts.insert(parts.end(), obj.parts.begin(), obj.parts.end());
  }
  return scan(std::move(parts), indices(n_target), model, sweep, std::move(f), seed, o.threads);
}

}  // namespace rangefit::sim
