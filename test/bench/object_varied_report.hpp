#pragma once
// object_benchmark --varied: object detection on seeded varied laser-stripe scenes
// (sim/varied_scene.hpp), the hardest realistic input we have: any triangulation angle and
// camera side, stand-off, profile step, noise and outliers, occluded, cut by the sweep's end,
// among look-alikes and clutter, on the stripe cell and the pan-tilt head. Reported per target
// and per factor, on the tuning seeds and, separately, on the held-out seeds.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "detect/object/object_detector.hpp"
#include "detect/object/superquadric.hpp"
#include "sim/varied_scene.hpp"
#include "test/detect/object_scenes.hpp"

namespace rangefit::bench {

struct VariedCase {
  std::uint64_t seed = 0;
  int repetition = 0;  // which detector seed (detector_seed)
  sim::VariedScene::Factors factors;
  bool found = false, tp = false;
  double ms = 0.0;
  // Where the time went: the search for hypotheses, and the vote with the confirmation of its
  // candidates (slides and turns of rejected ones included); and how many hypotheses ran.
  double search_ms = 0.0, confirm_ms = 0.0;
  int hypotheses = 0;
  double centre_mm = 0.0;  // a true positive's largest centre error over the target's parts
  std::string model;       // the model searched for (on an object-free scene, the absent one)
};

// A detection is a true positive when every part of the target is (thesis: centre < 3 mm, axis
// < 5 deg except for spheres).
inline bool all_parts_true(const ObjectDetectResult& r, const sim::VariedScene& s) {
  if (!r.found() || s.target_parts.empty()) return false;
  const DetectedInstance& inst = r.instances[0];
  for (std::size_t p = 0; p < s.target_parts.size(); ++p) {
    const sim::ScenePart& truth = s.parts[static_cast<std::size_t>(s.target_parts[p])];
    const bool sphere = truth.model.a1 == truth.model.a2 && truth.model.a2 == truth.model.a3 &&
                        truth.model.eps1 == 1.0 && truth.model.eps2 == 1.0;
    if (!test::true_positive(inst.parts[p].T_world_part, truth, !sphere)) return false;
  }
  return true;
}

// The detector's seed for repetition k of a scene: k = 0 is the scene's own seed, the others move
// only the detector's random draws (RANSAC seeds, trials), not the scene.
inline std::uint64_t detector_seed(std::uint64_t scene_seed, int k) {
  return scene_seed + (static_cast<std::uint64_t>(k) << 32);
}

// What one --varied report runs: the seeds, the sensor, the targets and how each is printed.
struct VariedRun {
  int seeds = 100;
  std::uint64_t first = 1;  // 1-based within the tuning set
  bool held_out = false;
  bool pan_tilt = false;
  bool two_cameras = false;  // stripe cell or head: a second camera across the laser plane
  bool sensor_known = true;
  bool per_factor = false;
  bool list_failures = false;
  // Each scene detected with this many detector seeds (detector_seed): one run's rate carries
  // the detector's own luck, about +-4 points on ~100 scenes; the rows then count every
  // (scene, detector seed) and the per-seed rates are printed beside them.
  int detector_seeds = 1;
  std::optional<sim::VariedTarget> only;
};

// The scene options of `target` under `run`.
inline sim::VariedSceneOptions scene_options(sim::VariedTarget target, const VariedRun& run) {
  sim::VariedSceneOptions so;
  so.target = target;
  so.pan_tilt = run.pan_tilt;
  if (run.two_cameras) so.two_camera_probability = 1.0;
  return so;
}

inline VariedCase run_varied_case(const VariedRun& run, sim::VariedTarget target,
                                  std::uint64_t seed, int repetition = 0) {
  const sim::VariedScene s = sim::make_varied_scene(scene_options(target, run), seed);
  ObjectDetectOptions o;
  o.seed = detector_seed(seed, repetition);
  if (run.sensor_known) o.sensor = s.view;
  const auto t0 = std::chrono::steady_clock::now();
  const ObjectDetectResult r = detect_object(s.model, s.cloud.points, o);
  VariedCase c;
  c.seed = seed;
  c.repetition = repetition;
  c.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  c.search_ms = r.time.hypotheses_ms;
  c.confirm_ms = r.time.vote_ms;
  c.hypotheses = r.hypotheses_evaluated;
  c.factors = s.factors;
  c.model = s.model.name;
  c.found = r.found();
  c.tp = all_parts_true(r, s);
  for (std::size_t p = 0; c.tp && p < s.target_parts.size(); ++p) {
    const sim::ScenePart& truth = s.parts[static_cast<std::size_t>(s.target_parts[p])];
    c.centre_mm = std::max(c.centre_mm,
                           test::pose_error(r.instances[0].parts[p].T_world_part, truth).centre_mm);
  }
  return c;
}

inline double median_of(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

struct Tally {
  int n = 0, tp = 0, wrong = 0, missed = 0;
  std::vector<double> ms, centre_mm;  // every case's time; the true positives' centre errors
  std::vector<double> search_ms, confirm_ms, hypotheses;  // every case's
  void add(const VariedCase& c) {
    ++n;
    c.tp ? ++tp : c.found ? ++wrong : ++missed;
    ms.push_back(c.ms);
    search_ms.push_back(c.search_ms);
    confirm_ms.push_back(c.confirm_ms);
    hypotheses.push_back(c.hypotheses);
    if (c.tp) centre_mm.push_back(c.centre_mm);
  }
  double median_ms() const { return median_of(ms); }
};

inline void print_tally_row(const std::string& name, const Tally& t, bool absent) {
  if (t.n == 0) return;
  const double n = t.n;
  if (absent) {  // object-free scenes: anything found is a false positive
    std::printf("  %-28s %5d   false positives %5.1f%%             %8.1f ms\n", name.c_str(), t.n,
                100.0 * t.wrong / n, t.median_ms());
    return;
  }
  std::printf(
      "  %-28s %5d   TP %5.1f%%  wrong %5.1f%%  missed %5.1f%%  %8.1f ms  TP centre %.2f mm\n",
      name.c_str(), t.n, 100.0 * t.tp / n, 100.0 * t.wrong / n, 100.0 * t.missed / n, t.median_ms(),
      median_of(t.centre_mm));
}

// A factor and its bins: a label per case, or "" to leave the case out of this factor.
struct Factor {
  const char* name;
  std::function<std::string(const sim::VariedScene::Factors&)> bin;
};

inline std::vector<Factor> varied_factors() {
  const auto range = [](double v, std::vector<double> edges, const char* unit) {
    for (std::size_t i = 1; i < edges.size(); ++i) {
      if (v < edges[i] || i + 1 == edges.size()) {
        char b[64];
        std::snprintf(b, sizeof b, "%g-%g %s", edges[i - 1], edges[i], unit);
        return std::string(b);
      }
    }
    return std::string();
  };
  return {
      {"sensor",
       [](const auto& f) { return std::string(f.scan.pan_tilt ? "pan-tilt" : "stripe"); }},
      {"triangulation",
       [=](const auto& f) {
         return range(f.scan.triangulation_deg, {15, 25, 35, 50}, "deg");
       }},
      {"camera side",
       [](const auto& f) {
         return std::string(f.scan.two_cameras ? "both" : f.scan.camera_side > 0 ? "+y" : "-y");
       }},
      {"laser height",
       [=](const auto& f) {
         return range(f.scan.laser_height_mm, {300, 500, 700, 900}, "mm");
       }},
      {"step",
       [=](const auto& f) {
         return range(f.scan.step_mm, {0.3, 0.8, 1.4, 2.0}, "mm");
       }},
      {"noise",
       [=](const auto& f) {
         return range(f.scan.noise_mm, {0, 0.3, 0.6, 1.0}, "mm");
       }},
      {"occlusion",
       [=](const auto& f) {
         return range(f.occlusion, {0, 0.2, 0.4, 0.6, 1.0}, "hidden");
       }},
      {"part lost",
       [=](const auto& f) {
         return range(f.part_lost, {0, 0.2, 0.4, 0.6, 1.0}, "of a part");
       }},
      {"look-alike ratio",
       [=](const auto& f) {
         return f.lookalikes ? range(f.lookalike_ratio, {0.04, 0.08, 0.14, 0.2}, "") : "";
       }},
  };
}

// The rate of a row per detector seed ("93.5 / 96.3 / 95.3"), or "" with one detector seed.
inline std::string per_repetition(const std::vector<VariedCase>& cases, int repetitions,
                                  bool absent, const std::function<bool(const VariedCase&)>& in) {
  if (repetitions < 2) return "";
  std::string out = "   per detector seed:";
  for (int k = 0; k < repetitions; ++k) {
    Tally t;
    for (const VariedCase& c : cases) {
      if (c.repetition == k && in(c)) t.add(c);
    }
    char b[32];
    std::snprintf(b, sizeof b, "%s%.1f", k ? " / " : " ",
                  t.n ? 100.0 * (absent ? t.wrong : t.tp) / t.n : 0.0);
    out += b;
  }
  return out;
}

// One block of the report: every target (or only `run.only`) over `run.seeds` seeds from
// `first`.
inline void print_varied_block(const char* title, std::uint64_t first, const VariedRun& run) {
  const int seeds = run.seeds;
  std::printf("\n%s: seeds %llu..%llu, %s, sensor %s, %d detector seed%s per scene\n", title,
              static_cast<unsigned long long>(first),
              static_cast<unsigned long long>(first + static_cast<std::uint64_t>(seeds) - 1),
              run.pan_tilt      ? (run.two_cameras ? "pan-tilt head, two cameras" : "pan-tilt head")
              : run.two_cameras ? "stripe cell, two cameras"
                                : "stripe cell",
              run.sensor_known ? "known" : "unknown", run.detector_seeds,
              run.detector_seeds == 1 ? "" : "s");
  const sim::VariedTarget targets[] = {sim::VariedTarget::kSphere, sim::VariedTarget::kCylinder,
                                       sim::VariedTarget::kBox,    sim::VariedTarget::kCone,
                                       sim::VariedTarget::kMallet, sim::VariedTarget::kThreeSpheres,
                                       sim::VariedTarget::kNone};
  std::map<std::string, Tally> found;  // per model: its true positives
  for (sim::VariedTarget target : targets) {
    if (run.only && target != *run.only) continue;
    std::vector<VariedCase> cases;
    for (int k = 0; k < run.detector_seeds; ++k) {
      for (int i = 0; i < seeds; ++i) {
        cases.push_back(run_varied_case(run, target, first + static_cast<std::uint64_t>(i), k));
      }
    }
    const bool absent = target == sim::VariedTarget::kNone;
    const auto light = [](const VariedCase& c) { return c.factors.occlusion <= 0.4; };
    const auto seen = [](const VariedCase& c) { return c.factors.part_lost <= 0.4; };
    const auto any = [](const VariedCase&) { return true; };
    const auto row = [&](const char* name, const std::function<bool(const VariedCase&)>& in) {
      Tally t;
      for (const VariedCase& c : cases) {
        if (in(c)) t.add(c);
      }
      print_tally_row(name, t, absent);
      const std::string spread = per_repetition(cases, run.detector_seeds, absent, in);
      if (!spread.empty()) std::printf("  %s\n", spread.c_str());
    };
    std::printf("%s\n", sim::to_string(target));
    row("all", any);
    // Occlusion is of the whole target; a compound target may have lost one part entirely to it
    // or to the sweep's end (a mallet with its shaft outside the scan): the second row counts
    // the cases where every part still shows 60 % of what the sensor would see of it.
    if (!absent) row("occlusion <= 40 %", light);
    if (!absent) row("each part lost <= 40 %", seen);
    if (!absent) {
      Tally tp;
      for (const VariedCase& c : cases) {
        if (c.tp) tp.add(c);
      }
      // The first target of a model: the lone sphere, not the three spheres.
      if (tp.n) found.emplace(cases.front().model, tp);
    } else {
      // An object-free scene searches for one of the models: its time beside the time the same
      // model takes where it is found (the true positives' median, when that target ran too).
      std::vector<std::string> models;
      for (const VariedCase& c : cases) {
        if (std::find(models.begin(), models.end(), c.model) == models.end()) {
          models.push_back(c.model);
        }
      }
      std::sort(models.begin(), models.end());
      for (const std::string& m : models) {
        Tally t;
        for (const VariedCase& c : cases) {
          if (c.model == m) t.add(c);
        }
        print_tally_row("searching " + m, t, true);
        const auto it = found.find(m);
        if (it != found.end() && it->second.median_ms() > 0.0) {
          const Tally& f = it->second;
          std::printf("  %-28s %.2f x its found median (%.1f ms)\n", "",
                      t.median_ms() / f.median_ms(), f.median_ms());
          // The two stages beside those of the true positives (medians): an absent part runs every
          // hypothesis and judges every candidate the vote offers.
          std::printf(
              "  %-28s search %.1f ms (%.0f hypotheses) and confirmation %.1f ms, against "
              "%.1f ms (%.0f) and %.1f ms found\n",
              "", median_of(t.search_ms), median_of(t.hypotheses), median_of(t.confirm_ms),
              median_of(f.search_ms), median_of(f.hypotheses), median_of(f.confirm_ms));
        }
      }
    }
    if (run.list_failures) {
      // The seeds to look at with --varied-case: what went wrong, and how hidden the target was.
      for (const VariedCase& c : cases) {
        if (absent ? !c.found : c.tp) continue;
        std::printf(
            "    seed %llu (detector seed %d) %s occlusion %.2f (%s) part lost %.2f "
            "noise %.2f\n",
            static_cast<unsigned long long>(c.seed), c.repetition, c.found ? "wrong" : "missed",
            c.factors.occlusion, c.factors.occluder.c_str(), c.factors.part_lost,
            c.factors.scan.noise_mm);
      }
    }
    if (!run.per_factor) continue;
    for (const Factor& f : varied_factors()) {
      std::vector<std::pair<std::string, Tally>> bins;
      for (const VariedCase& c : cases) {
        const std::string b = f.bin(c.factors);
        if (b.empty()) continue;
        auto it =
            std::find_if(bins.begin(), bins.end(), [&](const auto& x) { return x.first == b; });
        if (it == bins.end()) it = bins.insert(bins.end(), {b, Tally{}});
        it->second.add(c);
      }
      std::sort(bins.begin(), bins.end(),
                [](const auto& a, const auto& b) { return a.first < b.first; });
      for (const auto& [b, t] : bins) print_tally_row(std::string(f.name) + " " + b, t, absent);
    }
  }
}

// One varied case in detail (object_benchmark --varied-case TARGET SEED): what was drawn, what
// came back, the checks the rejected candidates failed, and which scene part each reported or
// rejected place is on (the nearest part centre), to see what a false positive was made of.
inline void print_varied_case(const VariedRun& run, sim::VariedTarget target, std::uint64_t seed,
                              int repetition = 0) {
  const sim::VariedScene s = sim::make_varied_scene(scene_options(target, run), seed);
  ObjectDetectOptions o;
  o.seed = detector_seed(seed, repetition);
  if (run.sensor_known) o.sensor = s.view;
  const ObjectDetectResult r = detect_object(s.model, s.cloud.points, o);
  const auto& f = s.factors;
  std::printf(
      "%s seed %llu: %s, triangulation %.0f deg, camera %s, laser %.0f mm, step %.2f mm, "
      "noise %.2f mm, occlusion %.2f (%s), outside %.2f, look-alikes %d x %.3f, "
      "clutter %d, %zu points\n",
      sim::to_string(target), static_cast<unsigned long long>(seed),
      f.scan.pan_tilt ? "pan-tilt" : "stripe", f.scan.triangulation_deg,
      f.scan.two_cameras       ? "both sides"
      : f.scan.camera_side > 0 ? "+y"
                               : "-y",
      f.scan.laser_height_mm, f.scan.step_mm, f.scan.noise_mm, f.occlusion, f.occluder.c_str(),
      f.outside, f.lookalikes, f.lookalike_ratio, f.clutter, s.cloud.points.size());
  for (std::size_t i = 0; i < s.parts.size(); ++i) {
    const sim::ScenePart& p = s.parts[i];
    const Eigen::Vector3d c = p.T_world_part.translation();
    const Eigen::Vector3d z = p.T_world_part.linear().col(2), x = p.T_world_part.linear().col(0);
    std::printf(
        "  part %zu %-22s a %.1f %.1f %.1f e %.2f %.2f at %.1f %.1f %.1f axis %.2f %.2f %.2f x %.2f "
        "%.2f %.2f\n",
        i, p.name.c_str(), p.model.a1, p.model.a2, p.model.a3, p.model.eps1, p.model.eps2, c.x(),
        c.y(), c.z(), z.x(), z.y(), z.z(), x.x(), x.y(), x.z());
    // The scan points on it (G within 10 % of 1): a part with none was hidden or outside the sweep.
    int on = 0;
    for (const Eigen::Vector3d& q : s.cloud.points) {
      if (q.allFinite() && std::abs(metric_world(p.model, p.T_world_part, q) - 1.0) < 0.1) ++on;
    }
    std::printf("    %d scan points on it\n", on);
  }
  const auto nearest = [&](const Eigen::Vector3d& c) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < s.parts.size(); ++i) {
      if ((s.parts[i].T_world_part.translation() - c).norm() <
          (s.parts[best].T_world_part.translation() - c).norm()) {
        best = i;
      }
    }
    return s.parts.empty() ? std::string("-")
                           : s.parts[best].name + " " +
                                 std::to_string(static_cast<int>(
                                     (s.parts[best].T_world_part.translation() - c).norm())) +
                                 " mm";
  };
  std::printf(
      "  result: %s, tp %d, %d hypotheses, %.1f ms (plane %.1f, index %.1f, hypotheses %.1f, "
      "vote and confirmation %.1f)\n",
      to_string(r.reason), all_parts_true(r, s) ? 1 : 0, r.hypotheses_evaluated, r.time.total_ms,
      r.time.plane_ms, r.time.search_index_ms, r.time.hypotheses_ms, r.time.vote_ms);
  for (const DetectedInstance& inst : r.instances) {
    for (std::size_t l = 0; l < inst.link_angle_error_rad.size(); ++l) {
      std::printf("  link %zu: A %.3f rad D %.1f mm B %.3f rad\n", l, inst.link_angle_error_rad[l],
                  inst.link_distance_error_mm[l], inst.link_bearing_error_rad[l]);
    }
    for (const DetectedPart& p : inst.parts) {
      const PartScores& sc = p.scores;
      std::printf(
          "  found %s at %.1f %.1f %.1f axis %.2f %.2f %.2f x %.2f %.2f %.2f (%s): M %.3f I %zu S %zu cover %.2f of %d/%d "
          "seen-through %.2f open end %.2f rim %.2f size %d %.3f residual %.2f continues %.3f lowest %.2f "
          "below %.2f (sigma %.3f)\n",
          p.name.c_str(), p.center().x(), p.center().y(), p.center().z(), p.z_axis().x(),
          p.z_axis().y(), p.z_axis().z(), p.T_world_part.linear()(0, 0),
          p.T_world_part.linear()(1, 0), p.T_world_part.linear()(2, 0), nearest(p.center()).c_str(), sc.measure, sc.interior, sc.surface, sc.coverage,
          sc.measurable, sc.facing, sc.seen_through, sc.open_end, sc.open_rim, sc.size_determined ? 1 : 0,
          sc.size_scale, sc.residual_mm, sc.continuation, sc.lowest_mm, sc.below_plane_mm,
          sc.height_sigma_mm);
    }
  }
  for (const Rejection& j : r.rejections) {
    std::printf("  rejected part %zu at %.1f %.1f %.1f (%s): %s %.3f limit %.3f\n", j.part,
                j.centre.x(), j.centre.y(), j.centre.z(), nearest(j.centre).c_str(),
                to_string(j.check), j.value, j.limit);
  }
}

// The tuning seeds (from `run.first`, 1-based within the tuning set, so that a widened tuning
// set can be run without repeating seeds already looked at), or the held-out seeds (never looked
// at while tuning: run them only to report, always from the first one).
inline void print_varied(const VariedRun& run) {
  if (run.held_out) {
    print_varied_block("Held-out seeds", sim::kHeldOutSeedBase, run);
  } else {
    print_varied_block("Tuning seeds", sim::kTuningSeedBase + run.first - 1, run);
  }
}

}  // namespace rangefit::bench
