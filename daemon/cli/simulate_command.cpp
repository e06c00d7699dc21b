#include "daemon/cli/simulate_command.hpp"

#include <cmath>
#include <exception>
#include <fstream>
#include <functional>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "daemon/cli/commands.hpp"
#include "daemon/cli/json_util.hpp"
#include "fusion/css_assembler.hpp"
#include "fusion/profile_assembler.hpp"
#include "io/cloud_io.hpp"
#include "sim/css_simulator.hpp"
#include "sim/pan_tilt_head.hpp"
#include "sim/scene_loader.hpp"
#include "sim/sim_clock.hpp"
#include "sim/stripe_cell.hpp"

namespace rangefit::cli {
namespace {

using std::chrono::milliseconds;

struct SimulateArgs {
  std::string scene, sensor, out, truth, format;
  std::uint64_t seed = 1;
  bool exact = false;
  bool double_precision = false;
};

nlohmann::json pose_json(const Eigen::Isometry3d& T) {
  return {{"position", json_vec(T.translation())},
          {"x_axis", json_vec(T.linear().col(0))},
          {"z_axis", json_vec(T.linear().col(2))}};
}

nlohmann::json shape_json(const sim::Shape& shape) {
  nlohmann::json j;
  if (const auto* p = std::get_if<sim::PlaneShape>(&shape)) {
    j = {{"type", "plane"}, {"size", {p->size_x_mm, p->size_y_mm}}};
  } else if (const auto* b = std::get_if<sim::BoxShape>(&shape)) {
    j = {{"type", "box"}, {"size", json_vec(b->size_mm)}};
  } else if (const auto* c = std::get_if<sim::CylinderShape>(&shape)) {
    j = {{"type", "cylinder"}, {"radius", c->radius_mm}, {"height", c->height_mm}};
  } else if (const auto* s = std::get_if<sim::SphereShape>(&shape)) {
    j = {{"type", "sphere"}, {"radius", s->radius_mm}};
  } else if (const auto* q = std::get_if<sim::SuperquadricShape>(&shape)) {
    const Superquadric& m = q->model;
    j = {{"type", "superquadric"},
         {"a", {m.a1, m.a2, m.a3}},
         {"eps", {m.eps1, m.eps2}},
         {"taper", {m.kx, m.ky}}};
  } else if (const auto* m = std::get_if<sim::MeshShape>(&shape)) {
    j = {{"type", "mesh"}, {"source", m->source}, {"triangles", m->mesh.triangles.size()}};
  }
  return j;
}

nlohmann::json health_json(const hal::Device& d) {
  const hal::DeviceHealth h = d.health();
  return {{"device", d.name()},
          {"state", hal::to_string(h.state)},
          {"samples", h.counters.samples},
          {"gaps", h.counters.gaps},
          {"reconnects", h.counters.reconnects},
          {"message", h.message}};
}

// A simulated device that refuses start() or a move has a broken scene or options: stop there
// rather than write an empty or partial cloud.
void require(const hal::Status& s, std::string_view what) {
  if (!s) throw std::runtime_error(std::string(what) + ": " + s.message);
}

// Streams a simulated sensor and the device that moves it into the sensor's assembler, as the
// frames arrive, until `running` turns false: the one scan loop of every sensor.
template <class Frame, class Pose, class Assembler, class AddFrame, class AddPose>
fusion::FusedScan stream(hal::SampleSource<Frame>& sensor, hal::SampleSource<Pose>& motion,
                         Assembler& assembler, AddFrame add_frame, AddPose add_pose,
                         const std::function<bool()>& running, nlohmann::json& health) {
  assembler.begin_scan();
  require(sensor.start(), "sensor start");
  require(motion.start(), "motion start");
  std::vector<Frame> frames;
  std::vector<Pose> poses;
  while (running()) {
    frames.clear();
    poses.clear();
    motion.read(poses, milliseconds(100));
    sensor.read(frames, milliseconds(0));
    for (const auto& p : poses) add_pose(assembler, p);
    for (const auto& f : frames) add_frame(assembler, f);
  }
  health = {health_json(sensor), health_json(motion)};
  return assembler.finish();
}

// Scans the scene with the chosen sensor; returns the scan in the sensor's world frame, the
// pose of that frame in the scene and the devices' health.
fusion::FusedScan scan_scene(const sim::Scene& scene, const sim::RayCaster& caster,
                             const SimulateArgs& a, Eigen::Isometry3d& T_scene_world,
                             nlohmann::json& health) {
  sim::SimClock clock;
  const auto add_profile = [](auto& assembler, const hal::RangerProfile& p) {
    assembler.add_profile(p);
  };
  if (a.sensor == "css") {
    sim::CssScanOptions o;
    o.seed = a.seed;
    if (!a.exact) o.css_faults.range_noise_sigma_mm = 0.06;  // thesis 4.2.1: 60 um in depth
    sim::CssRig rig(scene, caster, o, clock);
    fusion::CssFusionConfig config;
    config.geometry = o.geometry;
    config.deflection_rad = o.deflection_rad;
    fusion::CssAssembler assembler(config);
    T_scene_world = scene.mounts.T_scene_css;
    return stream(
        rig.css(), rig.joint(), assembler,
        [](fusion::CssAssembler& f, const hal::CssRevolution& r) { f.add_revolution(r); },
        [](fusion::CssAssembler& f, const hal::JointSample& j) { f.add_joint(j); },
        [&] { return clock.now() < rig.scan_end() + milliseconds(300); }, health);
  }
  if (a.sensor == "stripe") {
    sim::StripeCellOptions o;
    o.seed = a.seed;
    o.quantise = !a.exact;
    sim::StripeCell cell(scene, caster, o, clock);
    fusion::StripeCellFusionConfig config;
    config.geometry = o.geometry;
    fusion::StripeCellAssembler assembler(config);
    require(cell.axis().enable(), "axis enable");
    require(cell.axis().move_to(o.geometry.axis_travel_mm, o.geometry.max_speed_mm_s), "axis move");
    T_scene_world = scene.mounts.T_scene_stripe;
    return stream(
        cell.ranger(), cell.axis(), assembler, add_profile,
        [](fusion::StripeCellAssembler& f, const hal::AxisSample& s) { f.add_axis(s); },
        [&] { return !cell.axis().motion_complete(); }, health);
  }
  sim::PanTiltOptions o;
  o.seed = a.seed;
  o.quantise = !a.exact;
  sim::PanTiltHead head(scene, caster, o, clock);
  fusion::PanTiltFusionConfig config;
  config.geometry = o.geometry;
  fusion::PanTiltAssembler assembler(config);
  T_scene_world = scene.mounts.T_scene_pantilt;
  return stream(
      head.ranger(), head.angles(), assembler, add_profile,
      [](fusion::PanTiltAssembler& f, const hal::PanTiltSample& s) { f.add_pan_tilt(s); },
      [&] { return clock.now() < head.sweep_end(); }, health);
}

int run(const SimulateArgs& a) {
  const sim::Scene scene = sim::load_scene(a.scene);
  const sim::RayCaster caster(scene);
  nlohmann::json health;
  Eigen::Isometry3d T_scene_world = Eigen::Isometry3d::Identity();
  fusion::FusedScan scan = scan_scene(scene, caster, a, T_scene_world, health);
  // Fusion works in the sensor's own world frame; the cloud is written in the scene's.
  for (auto& p : scan.cloud.points) p = T_scene_world * p;
  for (auto& n : scan.cloud.normals) n = T_scene_world.linear() * n;
  const auto precision = a.double_precision ? io::Precision::kFloat64 : io::Precision::kFloat32;
  std::optional<io::CloudFormat> format;
  if (!a.format.empty()) format = a.format == "pcd" ? io::CloudFormat::kPcd : io::CloudFormat::kPly;
  io::write_cloud(a.out, scan.cloud, precision, format);
  // With the cloud on stdout, the summary goes to stderr; and no truth file unless asked for.
  const bool piped = io::is_stdio(a.out);
  std::ostream& summary = piped ? std::cerr : std::cout;
  if (a.truth.empty()) {
    summary << "wrote " << scan.cloud.size() << " points to " << (piped ? "stdout" : a.out) << "\n";
    return kExitOk;
  }

  nlohmann::json truth;
  truth["scene"] = a.scene;
  truth["sensor"] = a.sensor;
  truth["seed"] = a.seed;
  truth["frame"] = "scene, mm";
  truth["points"] = scan.cloud.size();
  truth["fusion"] = {{"bad", scan.bad},
                     {"reason", scan.reason},
                     {"faults", scan.faults.total()},
                     {"dropped_frames", scan.dropped_frames}};
  truth["devices"] = health;
  for (const auto& o : scene.objects) {
    nlohmann::json j = shape_json(o.shape);
    j["name"] = o.name;
    j["pose"] = pose_json(o.T_world_object);
    truth["objects"].push_back(j);
  }
  truth["bores"] = nlohmann::json::array();
  for (const auto& b : scene.bores) {
    truth["bores"].push_back({{"name", b.name},
                              {"kind", b.kind},
                              {"diameter", b.diameter_mm},
                              {"opening", json_vec(b.opening_mm)},
                              {"axis", json_vec(b.axis)}});
  }
  std::ofstream out(a.truth);
  out << truth.dump(2) << "\n";
  if (!out) {
    std::cerr << "rangefit simulate: cannot write " << a.truth << "\n";
    return kExitBadInput;
  }
  summary << "wrote " << scan.cloud.size() << " points to " << (piped ? "stdout" : a.out)
          << ", ground truth to " << a.truth << "\n";
  return kExitOk;
}

}  // namespace

void add_simulate_command(CLI::App& app, int* exit_code) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "Scan a TOML scene with a simulated CSS, stripe cell or pan-tilt head; write the "
      "fused cloud and a ground-truth JSON (SCAN.truth.json unless --truth).");
  cmd->add_option("--scene", args->scene, "scene file (TOML, mm)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--sensor", args->sensor, "css | stripe | pantilt")
      ->required()
      ->check(CLI::IsMember({"css", "stripe", "pantilt"}));
  cmd->add_option("--seed", args->seed, "seed of all noise and faults");
  cmd->add_option("--out", args->out,
                  "cloud file to write (.ply or .pcd; - writes binary PLY to stdout)")
      ->required();
  cmd->add_option("--format", args->format, "ply | pcd: overrides the extension (with --out -)")
      ->check(CLI::IsMember({"ply", "pcd"}));
  cmd->add_flag("--double", args->double_precision,
                "write x y z and normals as float64 (default float32, what PCL and viewers read)");
  cmd->add_option("--truth", args->truth,
                  "ground-truth JSON to write (default OUT.truth.json; none with --out -)");
  cmd->add_flag("--exact", args->exact, "no noise and no chip quantisation");
  cmd->callback([args, exit_code] {
    if (args->truth.empty() && !io::is_stdio(args->out)) args->truth = args->out + ".truth.json";
    try {
      *exit_code = run(*args);
    } catch (const std::exception& e) {
      std::cerr << "rangefit simulate: " << e.what() << "\n";
      *exit_code = kExitBadInput;
    }
  });
}

}  // namespace rangefit::cli
