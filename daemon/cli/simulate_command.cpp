#include "daemon/cli/simulate_command.hpp"

#include <atomic>
#include <cmath>
#include <exception>
#include <fstream>
#include <functional>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "daemon/cell/fuse_views.hpp"
#include "daemon/cell/sim_cell.hpp"
#include "daemon/cell/sim_sensor.hpp"
#include "daemon/cli/commands.hpp"
#include "daemon/service/json_codec.hpp"
#include "io/cloud_io.hpp"
#include "sim/scene_loader.hpp"

namespace rangefit::cli {
namespace {

using daemon::json_vec;

using daemon::CellConfig;
using daemon::DeviceConfig;
using daemon::NamedHealth;
using daemon::ScanOutcome;
using daemon::ScanRequest;
using daemon::SimCell;

struct SimulateArgs {
  std::string scene, sensor, out, truth, format;
  std::uint64_t seed = 1;
  bool exact = false;
  bool double_precision = false;
  bool mirrored_camera = false;
};

// The --sensor spellings (SensorKind::cli_name, else its name) of the kinds the cell simulates.
std::vector<std::string> simulated_sensors() {
  std::vector<std::string> out;
  for (const daemon::SimSensor* s : daemon::all_sim_sensors()) {
    const daemon::SensorKind& k = *daemon::find_sensor_kind(s->kind);
    out.emplace_back(*k.cli_name != '\0' ? k.cli_name : k.name);
  }
  return out;
}

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

// The scan as rangefitd's simulated cell takes it (daemon/cell/sim_cell.hpp): the same sim/
// devices streaming into fusion through the service's scan loop, which checks every device's
// Status and health, with the device's default sweep. The cloud comes back in the scene's frame
// (no device extrinsics). health: the devices' state after the scan.
// With mirrored_camera, a second camera of the laser plane, mirrored to its other side, sweeps
// with the first (SimCell::scan_together) and the two views are fused as rangefitd fuses them.
ScanOutcome scan_scene(const SimulateArgs& a, nlohmann::json& health) {
  CellConfig config;
  config.sim.time_scale = 0.0;   // as fast as possible
  config.sim.seed = a.seed - 1;  // the cell seeds its n-th scan with seed + n: the first, a.seed
  config.sim.noise = !a.exact;
  DeviceConfig device;
  device.name = a.sensor;
  device.kind = *daemon::find_sensor_kind(a.sensor);  // a --sensor spelling of a kind
  device.scene = a.scene;
  config.devices.push_back(device);
  if (a.mirrored_camera) {
    device.name += "_b";
    config.devices.push_back(device);
    const hal::StripeCellGeometry& g = config.fusion.stripe_cell.geometry;
    config.fusion.stripe_cell.cameras.push_back(
        {device.name, g.ranger_position_cell_mm, g.ranger_rpy_cell_rad, -g.ranger.baseline_mm});
    config.fusion.pan_tilt.cameras.push_back(
        {device.name, -config.fusion.pan_tilt.geometry.ranger.baseline_mm});
  }
  SimCell cell(config);
  ScanRequest request;
  request.id = "simulate";
  request.sensor = config.devices.front().name;
  const std::atomic<bool> cancel{false};
  ScanOutcome out;
  if (a.mirrored_camera) {
    const DeviceConfig* both[] = {&config.devices[0], &config.devices[1]};
    std::vector<ScanOutcome> views = cell.scan_together(both, request, cancel, [] {});
    const std::string names[] = {config.devices[0].name, config.devices[1].name};
    if (views.empty())
      throw std::invalid_argument("--mirrored-camera: a " + a.sensor +
                                  " has no second camera (stripe, pantilt)");
    out = daemon::fuse_views(views, names, {.cameras = true});
  } else {
    out = cell.scan(config.devices.front(), request, cancel, [] {});
  }
  health = nlohmann::json::array();
  for (const NamedHealth& h : cell.health()) {
    health.push_back({{"device", h.name},
                      {"state", hal::to_string(h.health.state)},
                      {"samples", h.health.counters.samples},
                      {"gaps", h.health.counters.gaps},
                      {"reconnects", h.health.counters.reconnects},
                      {"message", h.health.message}});
  }
  return out;
}

int run(const SimulateArgs& a) {
  const sim::Scene scene = sim::load_scene(a.scene);  // the truth; the cell loads its own
  nlohmann::json health;
  const ScanOutcome scan = scan_scene(a, health);
  if (!scan.status) {
    std::cerr << "rangefit simulate: " << scan.status.message << "\n";
    return kExitBadInput;
  }
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
  truth["fusion"] = {{"bad", false}};  // a scan fusion marks bad is an error above
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
  std::string sensors;
  for (const std::string& s : simulated_sensors()) sensors += (sensors.empty() ? "" : " | ") + s;
  cmd->add_option("--sensor", args->sensor, sensors)
      ->required()
      ->check(CLI::IsMember(simulated_sensors()));
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
  cmd->add_flag("--mirrored-camera", args->mirrored_camera,
                "stripe, pantilt: a second camera mirrored across the laser plane sweeps with the "
                "first; the cloud is both cameras' points, as rangefitd fuses two cameras");
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
