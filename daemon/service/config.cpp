// TOML → DaemonConfig. Each table is read through a FieldReader that knows the dotted path of
// the table, so every error names the field; keys nobody reads are reported as unknown, which
// catches typos that would otherwise silently fall back to a default.
#include "daemon/service/config.hpp"

#include <toml++/toml.h>
#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

#include "api/listen_address.hpp"
#include "daemon/service/bus_addresses.hpp"
#include "daemon/service/ros_env.hpp"
#include "daemon/service/scan_types.hpp"
#include "io/object_model_file.hpp"
#include "io/toml_fields.hpp"
#include "io/toml_file.hpp"

namespace rangefit::daemon {
namespace {

using FieldReader = io::TomlFields;

constexpr double kMaxRotarySweepRad = 6.283185307179586;  // one turn
constexpr double kMaxLinearSweepMm = 1e4;
constexpr double kPi = 3.14159265358979323846;

void read_service(FieldReader& r, ServiceConfig& s) {
  std::int64_t capacity = static_cast<std::int64_t>(s.queue_capacity);
  r.read("queue_capacity", capacity, 1, 1024);
  s.queue_capacity = static_cast<std::size_t>(capacity);
  r.read("scan_timeout_s", s.scan_timeout_s, 0.1, 3600.0);
  r.read("stall_timeout_s", s.stall_timeout_s, 0.1, 3600.0);
  r.read("log_level", s.log_level);
  static const std::set<std::string> kLevels{"trace", "debug", "info", "warn", "error"};
  if (!kLevels.contains(s.log_level))
    r.fail("log_level", "must be trace, debug, info, warn or error");
  r.read("bore_sensor", s.bore_sensor);
  r.read("object_sensor", s.object_sensor);
  r.reject_unknown();
}

// Paths go into Cyclone's configuration, a comma-separated list of URIs and XML: no commas.
void read_path(FieldReader& r, std::string_view key, std::filesystem::path& out) {
  std::string path = out.string();
  r.read(key, path);
  if (path.find(',') != std::string::npos) r.fail(key, "must not contain ','");
  out = path;
}

void read_dds_security(FieldReader& r, DdsSecurityConfig& s) {
  for (const auto& [key, path] : DdsSecurityConfig::documents(s)) {
    read_path(r, key, *path);
    if (path->empty()) r.fail(key, "is required in [dds.security]");
  }
  read_path(r, "plugin_dir", s.plugin_dir);
  if (s.plugin_dir.empty()) r.fail("plugin_dir", "must not be empty");
  r.reject_unknown();
}

void read_dds(FieldReader& r, DdsConfig& d) {
  std::int64_t domain = d.domain_id;
  r.read("domain_id", domain, 0, 232);  // the DDSI port mapping allows domains 0..232
  d.domain_id = static_cast<std::uint32_t>(domain);
  r.read("config_uri", d.config_uri);
  r.read("diagnostics_period_s", d.diagnostics_period_s, 0.05, 60.0);
  std::int64_t depth = d.cloud_depth;
  r.read("cloud_depth", depth, 1, 100);
  d.cloud_depth = static_cast<int>(depth);
  depth = d.request_depth;
  r.read("request_depth", depth, 1, 1000);
  d.request_depth = static_cast<int>(depth);
  if (r.sub_table("security") != nullptr) {
    FieldReader sub = r.sub("security");
    read_dds_security(sub, d.security);
  }
  r.read("partition", d.partition);  // "": the default partition
  if (!d.partition.empty()) {
    if (auto why = check_partition(d.partition); !why.empty()) r.fail("partition", why);
  }
  r.reject_unknown();
}

void read_spool(FieldReader& r, SpoolConfig& s) {
  std::string dir = s.directory.string();
  r.read("directory", dir);
  if (dir.empty()) r.fail("directory", "must not be empty");
  s.directory = dir;
  std::int64_t bytes = static_cast<std::int64_t>(s.max_bytes);
  r.read("max_bytes", bytes, 1 << 20, std::numeric_limits<std::int64_t>::max());
  s.max_bytes = static_cast<std::uint64_t>(bytes);
  r.read("max_age_hours", s.max_age_hours, 0.001, 24.0 * 3650);
  r.read("pictures", s.pictures);
  r.reject_unknown();
}

void read_interface(FieldReader& r, InterfaceConfig& c) {
  r.read("listen", c.listen);
  std::string why;
  if (!c.listen.empty() && !api::parse_listen_address(c.listen, &why)) r.fail("listen", why);
  r.read("token", c.token);
  if (!c.token.empty()) {
    if (c.token.size() < 8 || c.token.size() > 256) r.fail("token", "must be 8..256 characters");
    for (const char ch : c.token) {
      if (ch <= 0x20 || ch > 0x7e) r.fail("token", "must be printable ASCII without spaces");
    }
  }
  std::int64_t bytes = static_cast<std::int64_t>(c.max_request_bytes);
  r.read("max_request_bytes", bytes, 1024, 16 << 20);
  c.max_request_bytes = static_cast<std::size_t>(bytes);
  r.reject_unknown();
}

void read_detection(FieldReader& r, DetectionConfig& d) {
  std::int64_t seed = static_cast<std::int64_t>(d.seed);
  r.read("seed", seed, 0, std::numeric_limits<std::int64_t>::max());
  d.seed = static_cast<std::uint64_t>(seed);
  r.read("timeout_s", d.timeout_s, 0.01, 3600.0);
  r.reject_unknown();
}

void read_sim(FieldReader& r, SimConfig& s) {
  std::string scene = s.scene.string();
  r.read("scene", scene);
  s.scene = scene;
  r.read("time_scale", s.time_scale, 0.0, 1000.0);
  std::int64_t seed = static_cast<std::int64_t>(s.seed);
  r.read("seed", seed, 0, std::numeric_limits<std::int64_t>::max());
  s.seed = static_cast<std::uint64_t>(seed);
  r.read("noise", s.noise);
  r.reject_unknown();
}

void read_sim_fault(FieldReader& r, SimFaultConfig& f) {
  r.read("disconnect_after_s", f.disconnect_after_s, -1.0, 1e6);
  r.read("disconnect_for_s", f.disconnect_for_s, 0.0, 1e6);
  std::int64_t scan = f.on_scan;
  r.read("on_scan", scan, 0, 1000000);
  f.on_scan = static_cast<int>(scan);
  r.reject_unknown();
}

std::string describe(const CanNodeUse& u) {
  return std::to_string(u.node) + (u.is_default ? " (the default)" : "");
}

// "pan_tilt, robot or stripe": the kinds that read that field.
std::string kinds_with(bool KindFields::*field) {
  return sensor_kind_names([field](const SensorKind& k) { return k.fields.*field; });
}

// CANopen node ids are 1..127; Modbus unit ids 1..247 (0 is broadcast, 248.. reserved).
void read_bus_addresses(FieldReader& r, DeviceConfig& d) {
  struct Address {
    const char* key;
    int* out;
    std::int64_t max;
    bool KindFields::*field;
  };
  for (const Address& a : {Address{"can_node", &d.can_node, 127, &KindFields::can_node},
                           Address{"pan_node", &d.pan_node, 127, &KindFields::pan_node},
                           Address{"tilt_node", &d.tilt_node, 127, &KindFields::tilt_node},
                           Address{"modbus_unit", &d.modbus_unit, 247, &KindFields::modbus_unit}}) {
    std::int64_t v = 0;
    r.read(a.key, v, 1, a.max);
    if (v != 0 && !(d.kind->fields.*a.field)) r.fail(a.key, "only for kind " + kinds_with(a.field));
    *a.out = static_cast<int>(v);
  }
  // The head's three nodes share its interface.
  const auto nodes = can_nodes(d);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (nodes[i].node == nodes[j].node) {
        r.fail(nodes[i].field,
               "CAN node " + describe(nodes[i]) + " is also this device's " + nodes[j].field);
      }
    }
  }
}

// Real devices on one CAN interface must not share a node id (their frames would mix); the
// error names both devices and the fields that set the ids (defaults count too).
void check_can_nodes(const std::vector<DeviceConfig>& devices, std::size_t i, FieldReader& r) {
  const DeviceConfig& d = devices[i];
  if (d.driver != DriverKind::kReal) return;
  for (const CanNodeUse& mine : can_nodes(d)) {
    for (std::size_t k = 0; k < i; ++k) {
      const DeviceConfig& other = devices[k];
      if (other.driver != DriverKind::kReal || other.transport != d.transport) continue;
      for (const CanNodeUse& theirs : can_nodes(other)) {
        if (theirs.node != mine.node) continue;
        r.fail(mine.field, "CAN node " + describe(mine) + " on " + d.transport +
                               " is also used by device \"" + other.name + "\" (devices[" +
                               std::to_string(k) + "]." + theirs.field + ")");
      }
    }
  }
}

void read_device(FieldReader& r, DeviceConfig& d) {
  r.read("name", d.name);
  if (d.name.empty()) r.fail("name", "is required");
  std::string kind;
  r.read("kind", kind);
  const SensorKind* known = find_sensor_kind(kind);
  if (known == nullptr || kind != known->name) {
    r.fail("kind", "must be one of " + sensor_kind_names({}, ", "));
  }
  d.kind = *known;
  std::string driver = "sim";
  r.read("driver", driver);
  if (driver == "sim") {
    d.driver = DriverKind::kSim;
  } else if (driver == "real") {
    d.driver = DriverKind::kReal;
  } else if (driver == "replay") {
    d.driver = DriverKind::kReplay;
  } else {
    r.fail("driver", "must be one of sim, real, replay");
  }
  r.read("transport", d.transport);
  if (d.driver == DriverKind::kReal && d.transport.empty()) {
    r.fail("transport", "is required for driver = \"real\" (e.g. \"can0\" or \"10.0.0.5:502\")");
  }
  std::string replay;
  r.read("replay_file", replay);
  d.replay_file = replay;
  if (d.driver == DriverKind::kReplay && replay.empty()) {
    r.fail("replay_file", "is required for driver = \"replay\"");
  }
  r.read("xyz_mm", d.xyz_mm, -1e5, 1e5);
  r.read("rpy_rad", d.rpy_rad, -2 * kPi, 2 * kPi);
  // The sweep decides how many points a scan produces (sensor rate x sweep time): a CSS sweep of
  // +-30 rad fused 3.6 M points. Rotary sweeps stay within one turn each way, linear ones within
  // 10 m; a slow speed is bounded by scan_timeout_s.
  const double sweep_limit = d.kind->sweep_linear ? kMaxLinearSweepMm : kMaxRotarySweepRad;
  r.read("sweep_start", d.sweep_start, -sweep_limit, sweep_limit);
  r.read("sweep_end", d.sweep_end, -sweep_limit, sweep_limit);
  r.read("sweep_speed", d.sweep_speed, 0.0, d.kind->sweep_linear ? 1e5 : 100.0);
  r.read("motion", d.motion);
  std::string protocol;
  r.read("protocol", protocol);
  if (!protocol.empty()) {
    if (!d.kind->fields.protocol)
      r.fail("protocol", "only for kind " + kinds_with(&KindFields::protocol));
    if (protocol == "cia402") {
      d.protocol = JointProtocol::kCia402;
    } else if (protocol == "powercube") {
      d.protocol = JointProtocol::kPowerCube;
    } else {
      r.fail("protocol", "must be cia402 or powercube");
    }
  }
  read_bus_addresses(r, d);
  if (d.protocol == JointProtocol::kPowerCube && d.can_node > 31) {
    r.fail("can_node", "a PowerCube module id is 1 .. 31");
  }
  std::string scene;
  r.read("scene", scene);
  d.scene = scene;
  if (r.sub_table("sim_fault") != nullptr) {
    FieldReader sub = r.sub("sim_fault");
    read_sim_fault(sub, d.sim_fault);
  }
  r.reject_unknown();
}

std::filesystem::path resolve(const std::filesystem::path& p, const std::filesystem::path& base) {
  return p.empty() || p.is_absolute() || base.empty() ? p : base / p;
}

void read_object(FieldReader& r, ObjectModelConfig& o, const std::filesystem::path& base_dir) {
  r.read("name", o.name);
  std::string file;
  r.read("model", file);
  o.model_file = resolve(file, base_dir);
  if (!file.empty()) {
    for (const char* inline_key : {"scale_mm", "shape", "taper"}) {
      if (r.find(inline_key) != nullptr) {
        r.fail(inline_key, "is for inline models; the model file (model) gives the parts");
      }
    }
    try {
      o.model = io::read_object_model(o.model_file);
    } catch (const std::exception& e) {
      r.fail("model", e.what());
    }
    if (o.name.empty()) o.name = o.model.name;
  } else {
    if (o.name.empty()) r.fail("name", "is required (or give a model file: model = \"x.toml\")");
    r.read("scale_mm", o.scale_mm, 0.1, 1e5);
    if (o.scale_mm == std::array<double, 3>{})
      r.fail("scale_mm", "is required (three half-sizes, mm), or a model file (model)");
    r.read("shape", o.shape, 0.1, 2.0);
    r.read("taper", o.taper, -1.0, 1.0);
    o.model = inline_object(o.name, o.scale_mm, o.shape, o.taper).model;
  }
  if (o.name.empty()) r.fail("name", "is required (the model file has no name)");
  std::string mesh;
  r.read("mesh", mesh);
  o.mesh = mesh;
  r.reject_unknown();
}

// [ros]: namespace = "cell1" (a leading '/', as ROS spells absolute namespaces, is dropped).
void read_ros(FieldReader& r, DdsConfig& d) {
  r.read("namespace", d.ros_namespace);
  if (d.ros_namespace.starts_with('/')) d.ros_namespace.erase(0, 1);  // "/": the root, none
  if (!d.ros_namespace.empty()) {
    if (auto why = check_ros_namespace(d.ros_namespace); !why.empty()) r.fail("namespace", why);
  }
  r.read("distro", d.ros_distro);
  if (auto why = check_ros_distro(d.ros_distro); !why.empty()) r.fail("distro", why);
  r.reject_unknown();
}

// [frames]: world = "<frame id>" and, per device, <device name> = "<frame id>".
void read_frames(FieldReader& r, const toml::table& t, DaemonConfig& c) {
  r.read("world", c.frames.world);
  if (auto why = check_frame_id(c.frames.world); !why.empty()) r.fail("world", why);
  for (const auto& [key, value] : t) {
    const std::string name(key.str());
    if (name == "world") continue;
    if (c.device(name) == nullptr) r.fail(name, "is neither world nor a device name");
    std::string id;
    r.read(name, id);
    if (auto why = check_frame_id(id); !why.empty()) r.fail(name, why);
    c.frames.sensors[name] = id;
  }
}

// The [fusion] table belongs to fusion/ (fusion/config.hpp), which validates it the same way.
struct FusionTableError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Reads [name] with `read` when the file has the table.
template <typename Read>
void optional_table(FieldReader& r, const char* name, Read read) {
  if (r.sub_table(name) != nullptr) {
    FieldReader sub = r.sub(name);
    read(sub);
  }
}

// [[devices]]: unique names, CAN nodes not shared, scenes resolved, motion devices that exist.
void read_devices(FieldReader& r, DaemonConfig& c, std::string_view source_name,
                  const std::filesystem::path& base_dir) {
  std::set<std::string> names;
  if (const auto* arr = r.table_array("devices")) {
    for (std::size_t i = 0; i < arr->size(); ++i) {
      FieldReader sub = r.element("devices", *arr, i);
      DeviceConfig& d = c.devices.emplace_back();
      read_device(sub, d);
      if (!names.insert(d.name).second) sub.fail("name", "duplicate device name");
      check_can_nodes(c.devices, i, sub);
      d.scene = resolve(d.scene, base_dir);
      if (d.driver == DriverKind::kSim && d.scene.empty()) d.scene = c.sim.scene;
      if (d.driver == DriverKind::kSim && d.kind->scans && d.scene.empty()) {
        sub.fail("scene", "is required for a simulated " + std::string(d.kind.name()) +
                              " (or set sim.scene)");
      }
    }
  }
  for (std::size_t i = 0; i < c.devices.size(); ++i) {
    const std::string& m = c.devices[i].motion;
    if (!m.empty() && c.device(m) == nullptr) {
      throw io::TomlError(
          source_name, 0,
          "devices[" + std::to_string(i) + "].motion: no device named \"" + m + "\"");
    }
  }
  // A further camera of the stripe cell's or the head's laser plane is a device of that kind
  // and name.
  const auto check_cameras = [&](const auto& cameras, const char* table, const char* kind) {
    for (std::size_t i = 0; i < cameras.size(); ++i) {
      const DeviceConfig* d = c.device(cameras[i].name);
      if (d == nullptr || d->kind != DeviceKind(kind)) {
        throw io::TomlError(source_name, 0,
                            std::string("fusion.") + table + ".cameras[" + std::to_string(i) +
                                "].name: no " + kind + " device named \"" + cameras[i].name + "\"");
      }
    }
  };
  check_cameras(c.fusion.stripe_cell.cameras, "stripe_cell", "stripe");
  check_cameras(c.fusion.pan_tilt.cameras, "pan_tilt", "pan_tilt");
  // A pan_tilt device moved by another is a further camera on that head, which moves itself.
  for (std::size_t i = 0; i < c.devices.size(); ++i) {
    const DeviceConfig& d = c.devices[i];
    if (d.kind != DeviceKind("pan_tilt") || d.motion.empty()) continue;
    const DeviceConfig* head = c.device(d.motion);
    const std::string where = "devices[" + std::to_string(i) + "].";
    if (head->kind != d.kind || !head->motion.empty()) {
      throw io::TomlError(source_name, 0,
                          where + "motion: \"" + d.motion +
                              "\" is not a pan_tilt head (a pan_tilt device without motion)");
    }
    if (d.pan_node != 0 || d.tilt_node != 0) {
      throw io::TomlError(source_name, 0,
                          where + (d.pan_node != 0 ? "pan_node" : "tilt_node") +
                              ": a camera on another head has no axes of its own");
    }
  }
}

// [[objects]]: unique names.
void read_objects(FieldReader& r, DaemonConfig& c, const std::filesystem::path& base_dir) {
  std::set<std::string> names;
  if (const auto* arr = r.table_array("objects")) {
    for (std::size_t i = 0; i < arr->size(); ++i) {
      FieldReader sub = r.element("objects", *arr, i);
      read_object(sub, c.objects.emplace_back(), base_dir);
      if (!names.insert(c.objects.back().name).second) sub.fail("name", "duplicate object name");
    }
  }
}

// A field the config leaves out takes its value from ROS 2's environment, as a ROS 2 node would
// (dds.domain_id from ROS_DOMAIN_ID, ros.distro from ROS_DISTRO); a bad variable is an error.
template <class T, class FromEnv>
void from_ros_env(const toml::table& root, const char* table, const char* key,
                  std::string_view source_name, T& field, FromEnv from_env) {
  const toml::table* t = root[table].as_table();
  if (t != nullptr && t->contains(key)) return;
  try {
    field = from_env().value_or(field);
  } catch (const std::invalid_argument& e) {
    throw io::TomlError(source_name, 0,
                        std::string(table) + "." + key + " (not set): " + e.what());
  }
}

DaemonConfig read_root(const toml::table& root, std::string_view source_name,
                       const std::filesystem::path& base_dir) {
  DaemonConfig c;
  FieldReader r(&root, std::string(source_name));
  if (const auto* t = r.sub_table("fusion")) {
    auto fusion = fusion::parse_fusion_config(*t, source_name);
    if (!fusion.config) throw FusionTableError(fusion.error);
    c.fusion = *fusion.config;
  }
  optional_table(r, "sim", [&](FieldReader& sub) { read_sim(sub, c.sim); });
  c.sim.scene = resolve(c.sim.scene, base_dir);
  optional_table(r, "service", [&](FieldReader& sub) { read_service(sub, c.service); });
  optional_table(r, "http", [&](FieldReader& sub) { read_interface(sub, c.http); });
  optional_table(r, "tcp", [&](FieldReader& sub) { read_interface(sub, c.tcp); });
  if (!c.http.listen.empty() && c.http.listen == c.tcp.listen) {
    throw io::TomlError(source_name, 0, "tcp.listen: the same address as http.listen");
  }
  optional_table(r, "dds", [&](FieldReader& sub) { read_dds(sub, c.dds); });
  optional_table(r, "ros", [&](FieldReader& sub) { read_ros(sub, c.dds); });
  from_ros_env(root, "dds", "domain_id", source_name, c.dds.domain_id, ros_domain_id);
  from_ros_env(root, "ros", "distro", source_name, c.dds.ros_distro, ros_distro_from_env);
  for (const auto& [key, path] : DdsSecurityConfig::documents(c.dds.security)) {
    *path = resolve(*path, base_dir);
  }
  optional_table(r, "spool", [&](FieldReader& sub) { read_spool(sub, c.spool); });
  optional_table(r, "detection", [&](FieldReader& sub) { read_detection(sub, c.detection); });
  read_devices(r, c, source_name, base_dir);
  if (const auto* t = r.sub_table("frames")) {
    FieldReader sub = r.sub("frames");
    read_frames(sub, *t, c);
  }
  read_objects(r, c, base_dir);
  r.reject_unknown();
  for (const auto* key : {"bore_sensor", "object_sensor"}) {
    const std::string& sensor =
        std::string_view(key) == "bore_sensor" ? c.service.bore_sensor : c.service.object_sensor;
    if (!sensor.empty() && c.device(sensor) == nullptr) {
      throw io::TomlError(source_name, 0,
                          std::string("service.") + key + ": no device named \"" + sensor + "\"");
    }
  }
  return c;
}

}  // namespace

ObjectModelConfig inline_object(std::string name, std::array<double, 3> scale_mm,
                                std::array<double, 2> shape, std::array<double, 2> taper) {
  ObjectModelConfig o;
  o.name = std::move(name);
  o.scale_mm = scale_mm;
  o.shape = shape;
  o.taper = taper;
  o.model.name = o.name;
  o.model.parts.push_back({o.name, Superquadric{scale_mm[0], scale_mm[1], scale_mm[2], shape[0],
                                                shape[1], taper[0], taper[1]}});
  return o;
}

const char* to_string(DriverKind k) {
  switch (k) {
    case DriverKind::kSim:
      return "sim";
    case DriverKind::kReal:
      return "real";
    case DriverKind::kReplay:
      return "replay";
  }
  return "?";
}

const DeviceConfig* CellConfig::device(std::string_view name) const {
  for (const auto& d : devices) {
    if (d.name == name) return &d;
  }
  return nullptr;
}

const ObjectModelConfig* DetectorConfig::object(std::string_view name) const {
  for (const auto& o : objects) {
    if (o.name == name) return &o;
  }
  return nullptr;
}

ConfigResult parse_config(std::string_view toml_text, std::string_view source_name,
                          const std::filesystem::path& base_dir) {
  ConfigResult result;
  try {
    const toml::table root = io::parse_toml(toml_text, source_name);
    result.config = read_root(root, source_name, base_dir);
  } catch (const io::TomlError& e) {
    result.error = e.what();
  } catch (const FusionTableError& e) {
    result.error = e.what();  // already "<source>: fusion.<table>.<field>: <problem>"
  }
  return result;
}

ConfigResult load_config(const std::filesystem::path& path) {
  std::string text;
  try {
    text = io::read_toml_file(path);
  } catch (const io::TomlError& e) {
    return {std::nullopt, e.what()};
  }
  return parse_config(text, path.string(), path.parent_path());
}

}  // namespace rangefit::daemon
