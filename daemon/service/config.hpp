#pragma once
// rangefitd's configuration: one TOML file (systemd/rangefitd.toml is the documented sample).
// Every field has a default listed here; parse_config() validates every field and names the
// offending one and its line (e.g. "rangefitd.toml:12: devices[1].driver: must be one of sim,
// real, replay") on error.

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "daemon/service/frames_config.hpp"
#include "daemon/service/sensor_kind.hpp"
#include "detect/object/object_model.hpp"
#include "fusion/config.hpp"

namespace rangefit::daemon {

enum class DriverKind { kSim, kReal, kReplay };
const char* to_string(DriverKind k);

// How a driver = "real" robot's joint is read over CAN: a CiA 402 drive (node can_node) or a
// Schunk/AMTEC PowerCube module (module id can_node, 1..31).
enum class JointProtocol { kCia402, kPowerCube };

// Faults a simulated device injects (driver = "sim"): the sensor's link drops during a scan, as
// a USB or CAN device that is unplugged and plugged back in. For tests and demos.
struct SimFaultConfig {
  double disconnect_after_s = -1.0;  // after the scan starts, in device time; < 0: never
  double disconnect_for_s = 0.0;     // the link is back after this long
  int on_scan = 0;                   // only the n-th scan of the device (1-based); 0: every scan
};

struct DeviceConfig {
  std::string name;  // unique; requests name sensors by it
  DeviceKind kind;   // a registered kind (daemon/service/sensor_kinds/: css, stripe, ...)
  DriverKind driver = DriverKind::kSim;
  std::string transport;              // real driver: "can0", "/dev/ttyACM0", "10.0.0.5:502"
  std::filesystem::path replay_file;  // replay driver: a PLY cloud returned as each scan
  std::array<double, 3> xyz_mm{};     // sensor extrinsics: translation, mm
  std::array<double, 3> rpy_rad{};    // sensor extrinsics: roll, pitch, yaw, rad
  double sweep_start = 0.0;           // default sweep: mm (linear) or rad (rotary)
  double sweep_end = 0.0;
  double sweep_speed = 0.0;  // per second; 0 = device default
  // real: device moving this sensor (robot, axis); empty = the only one. pan_tilt: the head a
  // further camera rides on (sim and real); empty = a head of its own.
  std::string motion;
  // Bus addresses of a real device (daemon/driver_configs.hpp); 0 = the driver's default.
  int can_node = 0;     // robot: its joint's CiA 402 node (1); stripe, pan_tilt: the ranger (32)
  int pan_node = 0;     // pan_tilt: the pan axis' CiA 402 node (1)
  int tilt_node = 0;    // pan_tilt: the tilt axis' CiA 402 node (2)
  int modbus_unit = 0;  // axis: the drive's Modbus unit id (1)
  JointProtocol protocol = JointProtocol::kCia402;  // robot: protocol = "cia402" | "powercube"
  std::filesystem::path scene;                      // sim driver: scene TOML; empty = sim.scene
  SimFaultConfig sim_fault;                         // sim driver: [devices.sim_fault]
};

// An object model: a model file (io/object_model_file.hpp: parts with taper, compound links),
// or, as a shorthand, one inline superquadric. Either way `model` holds the validated model the
// detector gets, read when the configuration is loaded (start-up and reload).
struct ObjectModelConfig {
  std::string name;                   // requests name models by it; default: the file's name
  std::filesystem::path model_file;   // model TOML; relative: to the config file
  std::array<double, 3> scale_mm{};   // inline: superquadric half-sizes a1, a2, a3, mm
  std::array<double, 2> shape{1, 1};  // inline: exponents eps1, eps2 (0.1 .. 2)
  std::array<double, 2> taper{0, 0};  // inline: taper kx, ky along z (-1 .. 1)
  std::filesystem::path mesh;         // optional CAD mesh (STL) of the object
  ObjectModel model;                  // what detection uses
};

// The inline shorthand as code (tests, defaults): one part named after the model.
ObjectModelConfig inline_object(std::string name, std::array<double, 3> scale_mm,
                                std::array<double, 2> shape = {1, 1},
                                std::array<double, 2> taper = {0, 0});

// found/reason of a result are the detector's own (detect/); the daemon adds no gate of its own.
struct DetectionConfig {
  std::uint64_t seed = 1;   // every random algorithm is seeded from this
  double timeout_s = 30.0;  // detection longer than this is answered "detection timeout"
};

// The simulated cell (driver = "sim"): sim/ devices ray-cast a scene, fusion/ assembles them.
struct SimConfig {
  std::filesystem::path scene;  // scene TOML (data/scenes/*.toml); relative: to the config file
  double time_scale = 1.0;      // virtual seconds per real second; 0 = as fast as possible
  std::uint64_t seed = 1;       // seeds the devices' noise and faults (scan n uses seed + n)
  bool noise = true;            // sensor noise (CSS 60 um, thesis 4.2.1) and quantisation
};

// DDS Security (OMG DDS Security 1.1: authentication, access control, encryption) through
// Cyclone's builtin plugins, from [dds.security]; all six documents or none. Certificates and
// keys are PEM (the key unencrypted), governance and permissions S/MIME-signed by the
// permissions CA; scripts/make_dds_security.sh makes a test set. daemon/dds_security.hpp turns
// this into Cyclone's Domain/Security configuration.
struct DdsSecurityConfig {
  std::filesystem::path identity_ca;           // CA that signed every participant's identity
  std::filesystem::path identity_certificate;  // this daemon's identity certificate
  std::filesystem::path private_key;           // its private key
  std::filesystem::path permissions_ca;        // CA that signed governance and permissions
  std::filesystem::path governance;            // signed governance document (.p7s)
  std::filesystem::path permissions;           // signed permissions document (.p7s)
  // Cyclone's builtin security plugins (Debian 12: package libddsc0debian).
  std::filesystem::path plugin_dir = "/usr/lib/x86_64-linux-gnu/libddsc0debian";

  bool enabled() const { return !identity_ca.empty(); }
  bool operator==(const DdsSecurityConfig&) const = default;
  // The six documents by field name, as pointers into s (a DdsSecurityConfig, const or not),
  // for the code that reads, resolves and checks them.
  template <class Self>
  static auto documents(Self& s) {
    return std::array{std::pair{"identity_ca", &s.identity_ca},
                      std::pair{"identity_certificate", &s.identity_certificate},
                      std::pair{"private_key", &s.private_key},
                      std::pair{"permissions_ca", &s.permissions_ca},
                      std::pair{"governance", &s.governance},
                      std::pair{"permissions", &s.permissions}};
  }
};

struct DdsConfig {
  std::uint32_t domain_id = 0;        // 0 .. 232; not in the config: ROS_DOMAIN_ID, else 0
  std::string config_uri;             // Cyclone XML (file://...); empty = CYCLONEDDS_URI/default
  double diagnostics_period_s = 1.0;  // rt/diagnostics period (REP 107 expects ~1 Hz)
  int cloud_depth = 2;                // keep-last depth of rt/rangefit/cloud
  int request_depth =
      256;  // requests received, not yet taken (keep-all; the sender resends beyond)
  DdsSecurityConfig security;  // [dds.security]; off when absent
  // [dds] partition: the one DDS partition of every writer and reader; empty: the default one.
  // Cells in different partitions never match, also on rt/tf; ROS 2 nodes (rmw_cyclonedds) are
  // in the default partition only, so a ROS user sets a namespace instead (or as well).
  std::string partition;
  // [ros] namespace: the ROS namespace of rangefitd's topics and service ("cell1":
  // /cell1/rangefit/cloud, /cell1/rangefit/detect) and the prefix of its frame ids
  // ("cell1/world"); no leading or trailing '/' once read. Empty: none.
  std::string ros_namespace;
  // [ros] distro, else ROS_DISTRO, else "jazzy": the ROS 2 release whose graph lists the node.
  // "humble" publishes ros_discovery_info with Humble's 24-byte Gid; the others (iron, jazzy,
  // kilted, rolling) with the 16-byte Gid of Iron and later.
  std::string ros_distro = "jazzy";
};

struct SpoolConfig {
  std::filesystem::path directory = "/var/lib/rangefitd/spool";
  std::uint64_t max_bytes = 1ull << 30;  // oldest entries are removed beyond this size...
  double max_age_hours = 168.0;          // ...or this age
  bool pictures = true;                  // picture.png per entry with a scan (render/)
};

struct ServiceConfig {
  std::size_t queue_capacity = 4;  // waiting requests; beyond this a request is answered busy
  double scan_timeout_s = 120.0;   // a scan running longer is aborted with an error result
  double stall_timeout_s = 30.0;   // no pipeline progress this long: the watchdog is not fed
  std::string log_level = "info";  // trace | debug | info | warn | error
  std::string bore_sensor;         // default sensor for bore requests (a device name)
  std::string object_sensor;       // default sensor for object requests
};

// [http] and [tcp]: the interfaces for robot controllers and the browser page (api/), each off
// unless listen is set. Detections need the token; without one the interface is read-only.
struct InterfaceConfig {
  std::string listen;  // "127.0.0.1:8080" (HOST:PORT, numeric IPv4 or localhost); empty: off
  std::string token;   // write access; 8..256 printable ASCII characters, no spaces
  std::size_t max_request_bytes = 64 * 1024;  // a longer HTTP body or TCP line is refused
  bool operator==(const InterfaceConfig&) const = default;
};

// Each part of rangefitd is built from its own slice of the file: the cell (daemon/cell) from
// its devices, the simulated cell and the fusion geometry; detection from the seed, timeout and
// models; the DDS layer from DdsConfig; the spool from SpoolConfig. DaemonConfig is all of them.
struct CellConfig {
  SimConfig sim;
  fusion::FusionConfig fusion;  // [fusion], read by fusion::parse_fusion_config
  std::vector<DeviceConfig> devices;

  const DeviceConfig* device(std::string_view name) const;
};

struct DetectorConfig {
  DetectionConfig detection;
  std::vector<ObjectModelConfig> objects;

  const ObjectModelConfig* object(std::string_view name) const;
};

struct DaemonConfig : CellConfig, DetectorConfig {
  ServiceConfig service;
  InterfaceConfig http;  // [http]
  InterfaceConfig tcp;   // [tcp]
  DdsConfig dds;
  SpoolConfig spool;
  FramesConfig frames;  // [frames]: the names on the wire (ROS messages and TF)
};

struct ConfigResult {
  std::optional<DaemonConfig> config;  // set when valid
  std::string error;                   // "<source>[:<line>]: <field>: <problem>" when not
};

// Relative scene and security paths are resolved against base_dir (load_config: the config file's
// folder).
ConfigResult parse_config(std::string_view toml_text, std::string_view source_name = "config",
                          const std::filesystem::path& base_dir = {});
ConfigResult load_config(const std::filesystem::path& path);

}  // namespace rangefit::daemon
