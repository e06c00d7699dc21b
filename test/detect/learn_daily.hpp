#pragma once
// Teach-in scans of the thesis's daily-life objects (sim/daily_objects.hpp, tables 5.6 and 5.7)
// by a laser-stripe ranger (sim/stripe_scan.hpp), and their learning against the truth, for the
// learning test and the learn benchmark's report. The ranger is the pan-tilt head (the ranger
// turned about its laser line's axis, thesis eq. 5.7) looking at the object from 30-45 deg off
// vertical, or the stripe cell's linear sweep with its laser plane within 10 deg of vertical.
// The scan and the object's pose are drawn from the seed: triangulation angle 20-45 deg, camera
// side, ranger height 450-750 mm, profile step 0.5-1 mm, range noise 0.03-0.08 mm along the laser
// ray; the object anywhere within 60 mm of the middle of the scan, its yaw and (untapered parts)
// the face it rests on. The second view is a second sweep of the same ranger after the object
// was turned by 180 deg about the vertical through its middle (a turntable), its points turned
// back into the first view's frame before fusing.
//
// The cell's sweep from above lights the top faces only (its rays are within ~10 deg of
// vertical, so a side wall is grazed at best), and turning the object about the vertical shows
// it the same top again: from it an object's width is the extent of its top face, short by about
// half the sample spacing. The head's oblique view is the teach-in view.

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "detect/learn/model_learning.hpp"
#include "sim/daily_objects.hpp"
#include "sim/stripe_scan.hpp"
#include "sim/stripe_sweep.hpp"
#include "test/detect/learn_scenes.hpp"

namespace rangefit::test {

struct DailyTeach {
  sim::ScanSetup cell;
  std::vector<sim::ScenePart> parts;  // the object as it lies in the first view
  std::vector<Eigen::Vector3d> scan;  // table and object, all views fused, table frame
};

enum class TeachRig { kHead, kCell };

inline sim::ScanSetup daily_teach_setup(TeachRig rig, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto in = [&](double lo, double hi) { return lo + (hi - lo) * u(rng); };
  sim::ScanSetup s;
  s.pan_tilt = rig == TeachRig::kHead;
  s.triangulation_deg = in(20.0, 45.0);
  s.camera_side = u(rng) < 0.5 ? -1 : +1;
  s.laser_height_mm = in(450.0, 750.0);
  s.laser_tilt_deg = s.pan_tilt ? in(30.0, 45.0) : in(-10.0, 10.0);
  s.step_mm = in(0.5, 1.0);
  s.noise_mm = in(0.03, 0.08);
  s.max_points = 120000;
  return s;
}

// One scan of `parts` by the cell, over the parts' bounds and 40 mm of table around them.
inline std::vector<Eigen::Vector3d> stripe_points(const std::vector<sim::ScenePart>& parts,
                                                  const sim::ScanSetup& cell, std::uint64_t seed) {
  Eigen::AlignedBox3d cover;
  for (const sim::ScenePart& p : parts) {
    const sim::OrientedBox b = sim::oriented_bounds(p);
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d s((c & 1) ? 1.0 : -1.0, (c & 2) ? 1.0 : -1.0, (c & 4) ? 1.0 : -1.0);
      cover.extend(b.centre + b.axes * b.half.cwiseProduct(s));
    }
  }
  cover.min() -= Eigen::Vector3d(40.0, 40.0, 0.0);
  cover.max() += Eigen::Vector3d(40.0, 40.0, 5.0);
  cover.min().z() = 0.0;
  const sim::PartCaster caster(parts,
                               Eigen::AlignedBox2d(cover.min().head<2>(), cover.max().head<2>()));
  const sim::StripeSweep sweep = sim::make_sweep(cell, cover);
  sim::ScanNoise noise;
  noise.sigma_mm = cell.noise_mm;
  noise.seed = seed;
  return sim::scan_stripe(caster, sweep, noise, 1).cloud.points;
}

// The object of `object` drawn by `seed` and its teach-in scan of `views` (1 or 2) sweeps.
inline DailyTeach daily_teach(const sim::DailyObject& object, std::uint64_t seed, int views,
                              TeachRig rig = TeachRig::kHead) {
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ull + 17);
  DailyTeach t;
  t.cell = daily_teach_setup(rig, rng);
  std::uniform_real_distribution<double> off(-60.0, 60.0);
  const double x = kObjectX + off(rng), y = kObjectY + off(rng);
  t.parts = sim::resting_daily_object(object, x, y, rng).parts;
  for (int v = 0; v < views; ++v) {
    // View v: the object turned by v x 180 deg about the vertical through (x, y).
    Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
    turn.linear() =
        Eigen::AngleAxisd(v * 3.141592653589793, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    turn.translation() = Eigen::Vector3d(x, y, 0.0) - turn.linear() * Eigen::Vector3d(x, y, 0.0);
    std::vector<sim::ScenePart> turned = t.parts;
    for (sim::ScenePart& p : turned) p.T_world_part = turn * p.T_world_part;
    const std::vector<Eigen::Vector3d> pts =
        stripe_points(turned, t.cell, seed + static_cast<std::uint64_t>(v) * 7919);
    const Eigen::Isometry3d back = turn.inverse();
    for (const Eigen::Vector3d& p : pts) t.scan.push_back(back * p);
  }
  return t;
}

struct DailyLearnt {
  LearnResult result;
  std::vector<ShapeError> errors;  // per model part (the learnt part matched to it)
  double size = 1e9, shape = 1e9;  // worst over the parts
  double link_angle_rad = 0.0, link_distance_mm = 0.0;  // two parts: learnt link minus the truth
};

// Learns the object from its teach-in scan (parts as the model has) and compares every learnt
// part with the true part it lies on (the nearest centre).
inline DailyLearnt learn_daily(const sim::DailyObject& object, std::uint64_t seed, int views,
                               TeachRig rig = TeachRig::kHead, LearnOptions options = {}) {
  const DailyTeach t = daily_teach(object, seed, views, rig);
  options.parts = static_cast<int>(object.model.parts.size());
  options.name = object.name;
  DailyLearnt l;
  l.result = learn_model(t.scan, options);
  if (!l.result.learnt() || l.result.parts.size() != t.parts.size()) return l;
  l.size = l.shape = 0.0;
  for (std::size_t k = 0; k < t.parts.size(); ++k) {
    std::size_t best = 0;
    double best_d = 1e300;
    for (std::size_t j = 0; j < l.result.parts.size(); ++j) {
      const double d =
          (l.result.parts[j].T_world_part.translation() - t.parts[k].T_world_part.translation())
              .norm();
      if (d < best_d) best_d = d, best = j;
    }
    const LearntPart& p = l.result.parts[best];
    l.errors.push_back(
        shape_error(p.shape, p.T_world_part, object.model.parts[k].shape, t.parts[k].T_world_part));
    l.size = std::max(l.size, l.errors.back().size);
    l.shape = std::max(l.shape, l.errors.back().shape);
  }
  if (!object.model.links.empty() && !l.result.model.links.empty()) {
    l.link_angle_rad = l.result.model.links[0].angle_rad - object.model.links[0].angle_rad;
    l.link_distance_mm = l.result.model.links[0].distance_mm - object.model.links[0].distance_mm;
  }
  return l;
}

}  // namespace rangefit::test
